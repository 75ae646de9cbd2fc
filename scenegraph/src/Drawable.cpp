#include "throng/scenegraph/Drawable.h"

#include <stdexcept>

namespace throng {

Drawable::Drawable(std::string name, const BoundingSphere& localBound, std::uint64_t primitiveCount,
                   std::uint32_t morphTargetCount)
    : name_(std::move(name)), localBound_(localBound), primitiveCount_(primitiveCount), morphTargetCount_(morphTargetCount) {
    if (!localBound.valid())
        throw std::invalid_argument("Drawable '" + name_ + "': argument 'localBound' is empty");
}

Drawable::~Drawable() = default;

}  // namespace throng
