#include "throng/scenegraph/Transform.h"

#include <cmath>
#include <stdexcept>

#include "throng/scenegraph/NodeVisitor.h"
#include "throng/scenegraph/Validation.h"

namespace throng {

void Transform::accept(NodeVisitor& visitor) { visitor.apply(*this); }

void Transform::setMatrix(const Mat4& matrix) {
    constexpr std::string_view where = "Transform::setMatrix";
    requireFinite(matrix, where, "matrix", name());
    if (matrix[0][3] != 0.0 || matrix[1][3] != 0.0 || matrix[2][3] != 0.0 || matrix[3][3] != 1.0)
        throw std::invalid_argument(errorContext(where, name()) +
                                    ": argument 'matrix' is not affine (its last row is not 0 0 0 1)");
    local_ = matrix;
    usesDofs_ = false;
    localDirty_ = true;
    dirtyBound();
}

void Transform::setDofs(const TransformDofs& dofs) {
    constexpr std::string_view where = "Transform::setDofs";
    requireFinite(dofs.translation, where, "dofs.translation", name());
    requireFinite(dofs.rotation, where, "dofs.rotation", name());
    requireFinite(dofs.scale, where, "dofs.scale", name());
    const double len = glm::length(dofs.rotation);
    if (!(len > 0.0))
        throw std::invalid_argument(errorContext(where, name()) + ": argument 'dofs.rotation' is a zero quaternion");
    dofs_ = dofs;
    dofs_.rotation = dofs.rotation / len;
    usesDofs_ = true;
    localDirty_ = true;
    dirtyBound();
}

Mat4 Transform::localMatrix() const { return usesDofs_ && localDirty_ ? matrixFromDofs(dofs_) : local_; }

Mat4 matrixFromDofs(const TransformDofs& dofs, OpTally* ops) {
    const Quat& q = dofs.rotation;
    const double x2 = q.x + q.x, y2 = q.y + q.y, z2 = q.z + q.z;
    const double xx = q.x * x2, xy = q.x * y2, xz = q.x * z2;
    const double yy = q.y * y2, yz = q.y * z2, zz = q.z * z2;
    const double wx = q.w * x2, wy = q.w * y2, wz = q.w * z2;
    const Vec3& s = dofs.scale;
    Mat4 m(1.0);
    m[0] = Vec4((1.0 - (yy + zz)) * s.x, (xy + wz) * s.x, (xz - wy) * s.x, 0.0);
    m[1] = Vec4((xy - wz) * s.y, (1.0 - (xx + zz)) * s.y, (yz + wx) * s.y, 0.0);
    m[2] = Vec4((xz + wy) * s.z, (yz - wx) * s.z, (1.0 - (xx + yy)) * s.z, 0.0);
    m[3] = Vec4(dofs.translation, 1.0);
    THRONG_TALLY(ops, 18, 15, 0, 0);
    return m;
}

Mat4 composeAffine(const Mat4& a, const Mat4& b, OpTally* ops) {
    Mat4 r(1.0);
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row)
            r[c][row] = a[0][row] * b[c][0] + a[1][row] * b[c][1] + a[2][row] * b[c][2];
    for (int row = 0; row < 3; ++row)
        r[3][row] = a[0][row] * b[3][0] + a[1][row] * b[3][1] + a[2][row] * b[3][2] + a[3][row];
    THRONG_TALLY(ops, 36, 27, 0, 0);
    return r;
}

}  // namespace throng
