#pragma once
// A group whose children live in a frame given by a matrix, set directly or built from DOF values
// (translation, rotation, scale). Its world matrix is composed on the CPU by the matrices-and-bounds
// pass, which accounts the work under the node's cost category (NO_01 by default).

#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpCategory.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

/// DOF values from which a Transform builds its matrix: M = T(translation) * R(rotation) * S(scale).
struct TransformDofs {
    Vec3 translation{0.0};        ///< metres
    Quat rotation{1, 0, 0, 0};    ///< unit quaternion (normalized when set)
    Vec3 scale{1.0};              ///< per-axis scale factors
};

/// A group with a local affine transform.
class Transform : public Group {
public:
    void accept(NodeVisitor& visitor) override;

    /// Sets the local matrix. Throws std::invalid_argument if it is not finite or not affine
    /// (last row other than 0 0 0 1).
    void setMatrix(const Mat4& matrix);
    /// Sets the DOF values; the matrix is built from them by the next pass. Throws
    /// std::invalid_argument if a value is not finite or the rotation is a zero quaternion.
    void setDofs(const TransformDofs& dofs);
    /// The DOF values, if the transform is driven by DOFs.
    const TransformDofs& dofs() const { return dofs_; }
    /// Whether the matrix is built from DOF values (true) or was set directly (false).
    bool usesDofs() const { return usesDofs_; }

    /// The local matrix: the one set, or the one built from the current DOFs.
    Mat4 localMatrix() const;
    /// The world matrix as of the last matrices-and-bounds pass.
    const Mat4& worldMatrix() const { return world_; }

    /// Category under which this node's matrix work is counted (articulation, refpoint or root).
    OpCategory costCategory() const { return costCategory_; }
    /// Sets the cost category (the actors library marks Reference Point and Skeleton Root nodes).
    void setCostCategory(OpCategory category) { costCategory_ = category; }

private:
    friend class MatrixBoundsVisitor;
    Mat4 local_{1.0};
    Mat4 world_{1.0};
    TransformDofs dofs_;
    bool usesDofs_ = false;
    bool localDirty_ = false;
    OpCategory costCategory_ = OpCategory::SkeletonMatrix;
};

/// Builds T * R * S from DOF values (18 mults, 15 adds for the rotation-scale part).
Mat4 matrixFromDofs(const TransformDofs& dofs, OpTally* ops = nullptr);
/// Product a * b of two affine matrices on the CPU (36 mults, 27 adds: the last rows are not computed).
Mat4 composeAffine(const Mat4& a, const Mat4& b, OpTally* ops = nullptr);

}  // namespace throng
