#pragma once
// A scene's declaration that some static geometry hides what lies behind it (OSG's OccluderNode):
// boxes fitted inside the opaque geometry it stands beside, and the shell (that geometry's own
// bounding box). Occlusion culling rasterises the boxes; it leaves them out while the eye is inside
// the shell, where the geometry's inside (its back faces, not drawn) would not hide anything. The
// node draws nothing and adds nothing to its parent's bound.

#include <array>
#include <span>
#include <vector>

#include "throng/scenegraph/AxisBox.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/Node.h"

namespace throng {

/// Conservative occluder boxes of the geometry beside it, in its parent's frame.
class Occluder : public Node {
public:
    /// Occluder `boxes` (each inside the geometry, none empty) and the geometry's `shell` (which
    /// holds every box). Throws std::invalid_argument naming the box that is empty, not finite or
    /// not inside the shell.
    Occluder(std::vector<AxisBox> boxes, const AxisBox& shell);

    void accept(NodeVisitor& visitor) override;

    /// The boxes, in the parent's frame.
    std::span<const AxisBox> boxes() const { return boxes_; }
    /// The shell, in the parent's frame.
    const AxisBox& shell() const { return shell_; }
    /// World-space corners of box `i` (AxisBox::corner order), from the last matrices pass.
    const std::array<Vec3, 8>& worldCorners(std::size_t i) const { return world_[i]; }
    /// World-space bounding sphere of the boxes, from the last matrices pass.
    const BoundingSphere& worldOccluderBound() const { return occluderBound_; }
    /// Whether world point `eye` lies inside the world-axis box around the shell, grown by
    /// `margin` metres (a box at least as large as the shell: erring towards leaving boxes out).
    bool shellContains(const Vec3& eye, double margin) const;

    /// Places the boxes in the world (the node's own bound stays empty: it draws nothing).
    void updateMatricesAndBound(MatrixBoundsVisitor& visitor) override;

private:
    std::vector<AxisBox> boxes_;
    AxisBox shell_;
    std::vector<std::array<Vec3, 8>> world_;
    BoundingSphere occluderBound_;
    Vec3 shellMin_{0.0}, shellMax_{0.0};  // world-axis box around the shell
};

}  // namespace throng
