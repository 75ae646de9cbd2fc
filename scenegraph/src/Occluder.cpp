#include "throng/scenegraph/Occluder.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "throng/scenegraph/MatrixBoundsVisitor.h"
#include "throng/scenegraph/NodeVisitor.h"

namespace throng {
namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool inside(const AxisBox& box, const AxisBox& shell) {
    return box.min.x >= shell.min.x && box.min.y >= shell.min.y && box.min.z >= shell.min.z && box.max.x <= shell.max.x &&
           box.max.y <= shell.max.y && box.max.z <= shell.max.z;
}

}  // namespace

Occluder::Occluder(std::vector<AxisBox> boxes, const AxisBox& shell) : boxes_(std::move(boxes)), shell_(shell) {
    mayHoldOccluders_ = true;
    if (!finite(shell.min) || !finite(shell.max) || !(shell.volume() > 0.0))
        throw std::invalid_argument("Occluder: the shell is empty or not finite");
    for (std::size_t i = 0; i < boxes_.size(); ++i) {
        const AxisBox& b = boxes_[i];
        if (!finite(b.min) || !finite(b.max)) throw std::invalid_argument("Occluder: box " + std::to_string(i) + " is not finite");
        if (!(b.volume() > 0.0)) throw std::invalid_argument("Occluder: box " + std::to_string(i) + " is empty");
        if (!inside(b, shell)) throw std::invalid_argument("Occluder: box " + std::to_string(i) + " is not inside the shell");
    }
    world_.resize(boxes_.size());
}

void Occluder::accept(NodeVisitor& visitor) { visitor.apply(*this); }

void Occluder::updateMatricesAndBound(MatrixBoundsVisitor& visitor) {
    const Mat4& parent = visitor.parentWorld();
    BoundingSphere bound;
    for (std::size_t i = 0; i < boxes_.size(); ++i) {
        for (int c = 0; c < 8; ++c) world_[i][c] = Vec3(parent * Vec4(Vec3(boxes_[i].corner(c)), 1.0));
        const Vec3 centre = 0.5 * (world_[i][0] + world_[i][7]);
        double r2 = 0.0;
        for (const Vec3& p : world_[i]) r2 = std::max(r2, glm::dot(p - centre, p - centre));
        bound.expandBy(BoundingSphere(centre, std::sqrt(r2)));
    }
    occluderBound_ = bound;
    shellMin_ = shellMax_ = Vec3(parent * Vec4(Vec3(shell_.corner(0)), 1.0));
    for (int c = 1; c < 8; ++c) {
        const Vec3 p(parent * Vec4(Vec3(shell_.corner(c)), 1.0));
        shellMin_ = glm::min(shellMin_, p);
        shellMax_ = glm::max(shellMax_, p);
    }
    worldBound_ = BoundingSphere();  // draws nothing
}

bool Occluder::shellContains(const Vec3& eye, double margin) const {
    return eye.x >= shellMin_.x - margin && eye.x <= shellMax_.x + margin && eye.y >= shellMin_.y - margin &&
           eye.y <= shellMax_.y + margin && eye.z >= shellMin_.z - margin && eye.z <= shellMax_.z + margin;
}

}  // namespace throng
