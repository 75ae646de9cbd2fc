#pragma once
// A generic LOD node's work in CULL (NO_05), written once over the scalar type: the node's centre
// placed in the world, its squared distance to the eye, and the child whose range holds it.
// CullVisitor and LOD compile it for double, the FMULT tests for a counting type.

#include <cstdint>
#include <span>

#include <glm/mat4x4.hpp>

#include "throng/scenegraph/OpTally.h"

namespace throng::detail {

/// |world * center - eye|^2 * lodScale2: 13 mults, 14 adds.
template <class S>
S lodDistanceSquared(const glm::mat<4, 4, S, glm::defaultp>& world, const glm::vec<3, S, glm::defaultp>& center,
                     const glm::vec<3, S, glm::defaultp>& eye, S lodScale2, OpTally* ops) {
    using V = glm::vec<3, S, glm::defaultp>;
    const V worldCenter = V(world[0]) * center.x + V(world[1]) * center.y + V(world[2]) * center.z + V(world[3]);
    const V d = worldCenter - eye;
    THRONG_TALLY(ops, 13, 14, 0, 0);  // centre 9 + 9, difference 3, squared length 3 + 2, scale 1
    return glm::dot(d, d) * lodScale2;
}

/// Index of the first range whose squared end exceeds `distance2`, or -1: one comparison per range
/// looked at.
template <class S>
int selectRangeSquared(std::span<const double> maxDistances2, S distance2, OpTally* ops) {
    int index = -1;
    for (std::size_t i = 0; i < maxDistances2.size(); ++i)
        if (distance2 < S(maxDistances2[i])) {
            index = static_cast<int>(i);
            break;
        }
    THRONG_TALLY(ops, 0, index < 0 ? maxDistances2.size() : static_cast<std::size_t>(index) + 1, 0, 0);
    return index;
}

}  // namespace throng::detail
