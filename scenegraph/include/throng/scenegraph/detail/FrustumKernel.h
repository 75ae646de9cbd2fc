#pragma once
// Sphere-frustum classification with plane masks, written once over the scalar type: Frustum.cpp
// compiles it for double, the FMULT tests for a counting type.

#include <array>

#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/Frustum.h"

namespace throng::detail {

/// Classifies `s` against the planes of `planes` set in `mask`, clearing the bits of planes the
/// sphere is fully inside (see Frustum::classify). Per tested plane 3 mults and 5 adds (signed
/// distance, two comparisons); 1 add for the emptiness test; a sphere outside a plane stops early.
template <class S>
Containment classifySphere(const std::array<glm::vec<4, S, glm::defaultp>, Frustum::kPlaneCount>& planes,
                           const BasicBoundingSphere<S>& s, PlaneMask& mask, OpTally* ops) {
    THRONG_TALLY(ops, 0, 1, 0, 0);  // the emptiness test
    if (!s.valid()) return Containment::Outside;
    const auto& c = s.center();
    const S r = s.radius();
    for (int i = 0; i < Frustum::kPlaneCount; ++i) {
        const PlaneMask bit = static_cast<PlaneMask>(1u << i);
        if (!(mask & bit)) continue;
        const auto& p = planes[static_cast<std::size_t>(i)];
        const S dist = p.x * c.x + p.y * c.y + p.z * c.z + p.w;
        THRONG_TALLY(ops, 3, 4, 0, 0);  // signed distance, compare with -r (negation is free)
        if (dist < -r) return Containment::Outside;
        THRONG_TALLY(ops, 0, 1, 0, 0);  // compare with r
        if (dist >= r) mask = static_cast<PlaneMask>(mask & ~bit);
    }
    return mask == 0 ? Containment::Inside : Containment::Intersects;
}

}  // namespace throng::detail
