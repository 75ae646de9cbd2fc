#pragma once
// Local matrices from DOF values and affine products, written once over the scalar type:
// Transform.cpp compiles them for double, the FMULT tests for a counting type.

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include "throng/scenegraph/OpTally.h"

namespace throng::detail {

/// T(translation) * R(q) * S(scale) for a unit quaternion q (see throng::matrixFromDofs).
template <class S>
glm::mat<4, 4, S, glm::defaultp> matrixFromDofs(const glm::vec<3, S, glm::defaultp>& translation,
                                                const glm::qua<S, glm::defaultp>& q,
                                                const glm::vec<3, S, glm::defaultp>& s, OpTally* ops) {
    using V4 = glm::vec<4, S, glm::defaultp>;
    const S x2 = q.x + q.x, y2 = q.y + q.y, z2 = q.z + q.z;
    const S xx = q.x * x2, xy = q.x * y2, xz = q.x * z2;
    const S yy = q.y * y2, yz = q.y * z2, zz = q.z * z2;
    const S wx = q.w * x2, wy = q.w * y2, wz = q.w * z2;
    glm::mat<4, 4, S, glm::defaultp> m(S(1));
    m[0] = V4((S(1) - (yy + zz)) * s.x, (xy + wz) * s.x, (xz - wy) * s.x, S(0));
    m[1] = V4((xy - wz) * s.y, (S(1) - (xx + zz)) * s.y, (yz + wx) * s.y, S(0));
    m[2] = V4((xz + wy) * s.z, (yz - wx) * s.z, (S(1) - (xx + yy)) * s.z, S(0));
    m[3] = V4(translation, S(1));
    THRONG_TALLY(ops, 18, 15, 0, 0);
    return m;
}

/// a * b for affine matrices, last rows not computed (see throng::composeAffine).
template <class S>
glm::mat<4, 4, S, glm::defaultp> composeAffine(const glm::mat<4, 4, S, glm::defaultp>& a,
                                               const glm::mat<4, 4, S, glm::defaultp>& b, OpTally* ops) {
    glm::mat<4, 4, S, glm::defaultp> r(S(1));
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row)
            r[c][row] = a[0][row] * b[c][0] + a[1][row] * b[c][1] + a[2][row] * b[c][2];
    for (int row = 0; row < 3; ++row)
        r[3][row] = a[0][row] * b[3][0] + a[1][row] * b[3][1] + a[2][row] * b[3][2] + a[3][row];
    THRONG_TALLY(ops, 36, 27, 0, 0);
    return r;
}

}  // namespace throng::detail
