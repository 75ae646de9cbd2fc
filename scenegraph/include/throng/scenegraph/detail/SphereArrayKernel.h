#pragma once
// The per-sphere body of SphereArrayCuller, written once over the scalar type: the culler's
// vectorised loop runs it on float, the FMULT tests on a counting type.

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/detail/ScalarMath.h"

namespace throng::detail {

/// Six planes as the flat-array culler uses them: plane i = (nx[i], ny[i], nz[i], d[i]) relative to
/// the culler's origin, and margin[i] the rounding allowance of d[i].
template <class F>
struct CullPlanes {
    std::array<F, Frustum::kPlaneCount> nx{}, ny{}, nz{}, d{}, margin{};  ///< components and margins
};

/// Containment (0 outside, 1 crossing, 2 inside) of the sphere (cx, cy, cz, radius), with no branch
/// so that the loop vectorises across spheres: the smallest "distance + reach" over the planes says
/// whether it is outside one, the smallest "distance - reach" whether it is inside all.
template <class F>
inline std::uint8_t sphereContainment(F cx, F cy, F cz, F radius, const CullPlanes<F>& p) {
    // Relative rounding of float coordinates and of the dot product (a few ulps of each magnitude).
    constexpr float kRelMargin = 8.0f * std::numeric_limits<float>::epsilon();
    const F reach = radius + F(kRelMargin) * (absOf(cx) + absOf(cy) + absOf(cz) + radius);
    const F s0 = p.nx[0] * cx + p.ny[0] * cy + p.nz[0] * cz + p.d[0], s1 = p.nx[1] * cx + p.ny[1] * cy + p.nz[1] * cz + p.d[1];
    const F s2 = p.nx[2] * cx + p.ny[2] * cy + p.nz[2] * cz + p.d[2], s3 = p.nx[3] * cx + p.ny[3] * cy + p.nz[3] * cz + p.d[3];
    const F s4 = p.nx[4] * cx + p.ny[4] * cy + p.nz[4] * cz + p.d[4], s5 = p.nx[5] * cx + p.ny[5] * cy + p.nz[5] * cz + p.d[5];
    const auto& m = p.margin;
    // Lowest clearance over the planes, once widened by the reach (outside test) and once
    // narrowed by it (inside test).
    const F lowOut = std::min(std::min(std::min(s0 + m[0], s1 + m[1]), std::min(s2 + m[2], s3 + m[3])),
                              std::min(s4 + m[4], s5 + m[5])) + reach;
    const F lowIn = std::min(std::min(std::min(s0 - m[0], s1 - m[1]), std::min(s2 - m[2], s3 - m[3])),
                             std::min(s4 - m[4], s5 - m[5])) - reach;
    // Outside = 0, Intersects = 1, Inside = 2 (see Containment).
    return static_cast<std::uint8_t>(static_cast<int>(lowOut >= F(0)) + static_cast<int>(lowIn > F(0)));
}

}  // namespace throng::detail
