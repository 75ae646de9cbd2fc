#pragma once
// The view frustum as six normalized planes extracted from a view-projection matrix, with sphere
// classification and OpenSceneGraph-style plane masks: once a sphere is fully inside a plane, its
// descendants are not tested against that plane again.

#include <array>
#include <cstdint>

#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

/// Where a sphere lies relative to the frustum.
enum class Containment : std::uint8_t {
    Outside = 0,     ///< entirely outside at least one plane: nothing in it can be seen
    Intersects = 1,  ///< crosses at least one plane still being tested
    Inside = 2,      ///< inside every plane
};

/// One bit per frustum plane (bit i = plane i still needs testing).
using PlaneMask = std::uint8_t;

/// Six planes (left, right, bottom, top, near, far), each (n, d) with |n| = 1 and n·p + d >= 0 inside.
class Frustum {
public:
    /// Plane indices.
    enum Plane : int { kLeft = 0, kRight, kBottom, kTop, kNear, kFar, kPlaneCount };
    /// Mask with every plane set.
    static constexpr PlaneMask kAllPlanes = 0x3F;

    /// A frustum that contains everything (no active plane).
    Frustum() = default;
    /// Planes of the clip volume -w <= x, y, z <= w of `viewProjection` (OpenGL convention), in the
    /// space the matrix maps from. A plane whose normal vanishes (an infinite far plane) is inactive.
    /// Throws std::invalid_argument if the matrix is not finite or its volume is empty.
    static Frustum fromViewProjection(const Mat4& viewProjection);

    /// Plane `i` as (normal, offset).
    const Vec4& plane(int i) const { return planes_[static_cast<std::size_t>(i)]; }
    /// The planes that exist (an infinite far plane does not).
    PlaneMask activePlanes() const { return active_; }

    /// Classifies `sphere` against the planes set in `mask`, clearing the bits of planes the sphere
    /// is fully inside; a child of this sphere then needs only the remaining planes.
    Containment classify(const BoundingSphere& sphere, PlaneMask& mask, OpTally* ops = nullptr) const;
    /// Classifies `sphere` against every active plane.
    Containment classify(const BoundingSphere& sphere) const {
        PlaneMask mask = active_;
        return classify(sphere, mask);
    }
    /// Whether `point` is inside or on every active plane.
    bool contains(const Vec3& point) const;

private:
    std::array<Vec4, kPlaneCount> planes_{};
    PlaneMask active_ = 0;
};

}  // namespace throng
