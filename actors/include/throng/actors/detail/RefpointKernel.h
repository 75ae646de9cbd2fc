#pragma once
// The Reference Point's matrix on a closed-form path (RefpointPath), written once over the scalar
// type: RefpointPath.cpp compiles it for double, the FMULT tests for a counting type. Sine and
// cosine are priced as square roots; the comparison counts as an addition. The angle and the
// matrix are separate steps so a batch of paths can take its sines and cosines together
// (RefpointPath::atEach), with the same bits as one path alone.

#include <glm/mat4x4.hpp>

#include "throng/actors/detail/SinCos.h"
#include "throng/scenegraph/OpTally.h"
#include "throng/scenegraph/detail/ScalarMath.h"

namespace throng::detail {

/// Whether a path of `radius` walks a circle (else the Reference Point stands).
template <class W>
bool refpointOnCircle(W radius, OpTally* ops) {
    THRONG_TALLY(ops, 0, 1, 0, 0);  // radius > 0
    return radius > W(0);
}

/// The angle whose sine and cosine place and turn the Reference Point (refpointFromSinCos): on the
/// circle, the position angle at `time`; standing, the heading.
template <class W>
W refpointAngle(W heading, W radius, W speed, W time, bool onCircle, OpTally* ops) {
    if (onCircle) {
        THRONG_TALLY(ops, 1, 1, 1, 0);  // heading + (speed / radius) * time
        return heading + (speed / radius) * time;
    }
    return heading;
}

/// The matrix of a Reference Point at `center` (radius 0) or on the circle of `radius` round it,
/// given the sine and cosine of its refpointAngle.
template <class W>
glm::mat<4, 4, W, glm::defaultp> refpointFromSinCos(const glm::vec<3, W, glm::defaultp>& center, W radius, bool onCircle,
                                                    W sinA, W cosA, OpTally* ops) {
    using V4 = glm::vec<4, W, glm::defaultp>;
    glm::vec<3, W, glm::defaultp> position = center;
    W c = cosA, s = sinA;  // cosine and sine of the yaw
    THRONG_TALLY(ops, 0, 0, 0, 2);  // the sine and cosine (taken by the caller)
    if (onCircle) {
        // On the circle the actor faces along the tangent: yaw = theta + pi/2, so one sine and one
        // cosine serve both the position and the facing.
        position += glm::vec<3, W, glm::defaultp>(radius * sinA, W(0), radius * cosA);
        c = -sinA;
        s = cosA;
        THRONG_TALLY(ops, 2, 3, 0, 0);  // offset 2 mults, 3 adds
    }
    glm::mat<4, 4, W, glm::defaultp> m(W(1));
    m[0] = V4(c, W(0), -s, W(0));  // rotation about +Y: local +Z goes to (sin yaw, 0, cos yaw)
    m[2] = V4(s, W(0), c, W(0));
    m[3] = V4(position, W(1));
    return m;
}

/// The matrix of a Reference Point standing at `center` facing `heading`, or walking a circle of
/// `radius` round it at `speed` from angle `heading`, at `time` (see RefpointPath::at).
template <class W>
glm::mat<4, 4, W, glm::defaultp> refpointMatrix(const glm::vec<3, W, glm::defaultp>& center, W heading, W radius, W speed,
                                                W time, OpTally* ops) {
    const bool onCircle = refpointOnCircle(radius, ops);
    const W angle = refpointAngle(heading, radius, speed, time, onCircle, ops);
    W sinA, cosA;
    sinCos(angle, sinA, cosA);  // detail::sinCos for double; a counting type's own, by argument-dependent lookup
    return refpointFromSinCos(center, radius, onCircle, sinA, cosA, ops);
}

}  // namespace throng::detail
