#pragma once
// Drawable data shared by every Geometry leaf that shows it (clones of an actor share one).
// Renderers derive from it to carry vertex data; the scenegraph needs only its bound and size.

#include <cstdint>
#include <string>

#include "throng/scenegraph/BoundingSphere.h"

namespace throng {

/// Something a backend can draw: a bounding sphere in its own frame and a primitive count.
class Drawable {
public:
    /// A drawable named `name` (for statistics and errors) with `localBound` in its own frame and
    /// `morphTargetCount` morph targets (the weights a DrawItem of it carries). Throws
    /// std::invalid_argument if `localBound` is empty.
    Drawable(std::string name, const BoundingSphere& localBound, std::uint64_t primitiveCount,
             std::uint32_t morphTargetCount = 0);
    virtual ~Drawable();
    Drawable(const Drawable&) = delete;
    Drawable& operator=(const Drawable&) = delete;

    /// Name given at construction.
    const std::string& name() const { return name_; }
    /// Bounding sphere in the drawable's own frame.
    const BoundingSphere& localBound() const { return localBound_; }
    /// Number of primitives (triangles, or lines for line drawables) one draw sends.
    std::uint64_t primitiveCount() const { return primitiveCount_; }
    /// Number of morph targets: the length of DrawItem::morphWeights for items showing it.
    std::uint32_t morphTargetCount() const { return morphTargetCount_; }

private:
    std::string name_;
    BoundingSphere localBound_;
    std::uint64_t primitiveCount_;
    std::uint32_t morphTargetCount_;
};

}  // namespace throng
