#include "throng/scenegraph/Transform.h"

#include <cmath>
#include <stdexcept>

#include "throng/scenegraph/NodeVisitor.h"
#include "throng/scenegraph/Validation.h"
#include "throng/scenegraph/detail/TransformKernels.h"

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
    return detail::matrixFromDofs(dofs.translation, dofs.rotation, dofs.scale, ops);
}

Mat4 composeAffine(const Mat4& a, const Mat4& b, OpTally* ops) { return detail::composeAffine(a, b, ops); }

}  // namespace throng
