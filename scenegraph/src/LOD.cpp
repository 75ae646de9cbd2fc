#include "throng/scenegraph/LOD.h"

#include <cmath>
#include <stdexcept>

#include "throng/scenegraph/NodeVisitor.h"
#include "throng/scenegraph/Validation.h"
#include "throng/scenegraph/detail/LodKernels.h"

namespace throng {

void LOD::accept(NodeVisitor& visitor) { visitor.apply(*this); }

void LOD::addChild(std::shared_ptr<Node> child, double maxDistance) {
    auto where = [this] { return errorContext("LOD::addChild", name()); };
    requireFinite(maxDistance, "LOD::addChild", "maxDistance", name());
    if (maxDistance <= 0.0)
        throw std::invalid_argument(where() + ": argument 'maxDistance' must be positive (" +
                                    std::to_string(maxDistance) + ")");
    if (!maxDistances_.empty() && maxDistance <= maxDistances_.back())
        throw std::invalid_argument(where() + ": argument 'maxDistance' (" + std::to_string(maxDistance) +
                                    ") must exceed the previous child's (" +
                                    std::to_string(maxDistances_.back()) + ")");
    Group::addChild(std::move(child));
    maxDistances_.push_back(maxDistance);
    maxDistances2_.push_back(maxDistance * maxDistance);
}

void LOD::setDistanceScale(double scale) {
    requireFinite(scale, "LOD::setDistanceScale", "scale", name());
    if (scale <= 0.0)
        throw std::invalid_argument(errorContext("LOD::setDistanceScale", name()) + ": argument 'scale' must be positive (" +
                                    std::to_string(scale) + ")");
    distanceScale_ = scale;
}

void LOD::setCenter(const Vec3& center) {
    requireFinite(center, "LOD::setCenter", "center", name());
    center_ = center;
}

int LOD::selectChild(double distance) const {
    for (std::size_t i = 0; i < maxDistances_.size(); ++i)
        if (distance < maxDistances_[i]) return static_cast<int>(i);
    return -1;
}

int LOD::selectChildSquared(double distance2, OpTally* ops) const {
    return detail::selectRangeSquared(std::span<const double>(maxDistances2_), distance2, ops);
}

}  // namespace throng
