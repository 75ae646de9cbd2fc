#pragma once
// The Reference Point's matrix on a closed-form path (RefpointPath), written once over the scalar
// type: RefpointPath.cpp compiles it for double, the FMULT tests for a counting type. Sine and
// cosine are priced as square roots; the comparison counts as an addition.

#include <glm/mat4x4.hpp>

#include "throng/scenegraph/OpTally.h"
#include "throng/scenegraph/detail/ScalarMath.h"

namespace throng::detail {

/// The matrix of a Reference Point standing at `center` facing `heading`, or walking a circle of
/// `radius` round it at `speed` from angle `heading`, at `time` (see RefpointPath::at).
template <class W>
glm::mat<4, 4, W, glm::defaultp> refpointMatrix(const glm::vec<3, W, glm::defaultp>& center, W heading, W radius, W speed,
                                                W time, OpTally* ops) {
    using V4 = glm::vec<4, W, glm::defaultp>;
    glm::vec<3, W, glm::defaultp> position = center;
    W c, s;  // cosine and sine of the yaw
    THRONG_TALLY(ops, 0, 1, 0, 0);  // radius > 0
    if (radius > W(0)) {
        // On the circle the actor faces along the tangent: yaw = theta + pi/2, so one sine and one
        // cosine serve both the position and the facing.
        const W theta = heading + (speed / radius) * time;
        const W sinT = sinOf(theta), cosT = cosOf(theta);
        position += glm::vec<3, W, glm::defaultp>(radius * sinT, W(0), radius * cosT);
        c = -sinT;
        s = cosT;
        THRONG_TALLY(ops, 3, 4, 1, 2);  // angle 1 + 1 + 1 div, sin and cos, offset 2 mults, 3 adds
    } else {
        c = cosOf(heading);
        s = sinOf(heading);
        THRONG_TALLY(ops, 0, 0, 0, 2);
    }
    glm::mat<4, 4, W, glm::defaultp> m(W(1));
    m[0] = V4(c, W(0), -s, W(0));  // rotation about +Y: local +Z goes to (sin yaw, 0, cos yaw)
    m[2] = V4(s, W(0), c, W(0));
    m[3] = V4(position, W(1));
    return m;
}

}  // namespace throng::detail
