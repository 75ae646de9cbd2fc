#include "throng/scenegraph/CullVisitor.h"

#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/OcclusionBuffer.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/scenegraph/Transform.h"
#include "throng/scenegraph/Validation.h"
#include "throng/scenegraph/detail/LodKernels.h"

#include <stdexcept>

namespace throng {
namespace {
const Mat4 kIdentity(1.0);
}

CullVisitor::CullVisitor(const Camera& camera, DrawList& drawList, OpCounter* counter, double lodScale)
    : frustum_(camera.frustum()),
      eye_(camera.eye()),
      drawList_(drawList),
      counter_(counter),
      lodScale2_(lodScale * lodScale),
      mask_(frustum_.activePlanes()),
      world_(&kIdentity) {
    requireFinite(lodScale, "CullVisitor", "lodScale");
    if (!(lodScale > 0.0)) throw std::invalid_argument("CullVisitor: argument 'lodScale' must be positive");
}

void CullVisitor::setCullingFrustum(const Frustum& frustum) {
    frustum_ = frustum;
    mask_ = frustum_.activePlanes();
}

Containment CullVisitor::testSphere(const BoundingSphere& sphere, PlaneMask& mask) {
    if (!sphere.valid()) return Containment::Outside;
    if (mask == 0) return Containment::Inside;  // an ancestor is inside every plane
    ++stats_.spheresTested;
    OpTally* ops = nullptr;
    if (counter_) {
        counter_->countOperations(OpCategory::BsphereFrustumTest);
        ops = counter_->tally(OpCategory::BsphereFrustumTest);
    }
    return frustum_.classify(sphere, mask, ops);
}

void CullVisitor::addDrawItem(const DrawItem& item, std::uint64_t primitives, const Mat4& world,
                              std::span<const glm::mat4> palette) {
    drawList_.add(item, primitives, world, palette);
    ++stats_.drawItems;
    stats_.primitives += primitives;
}

bool CullVisitor::enter(const Node& node) {
    ++stats_.nodesVisited;
    rejectedByOcclusion_ = false;
    if (testSphere(node.worldBound(), mask_) == Containment::Outside) {
        ++stats_.nodesRejected;
        return false;
    }
    if (occlusion_) {
        ++stats_.occlusionTests;
        if (occlusion_->occluded(node.worldBound())) {
            ++stats_.nodesOccluded;
            rejectedByOcclusion_ = true;
            return false;
        }
    }
    return true;
}

void CullVisitor::apply(Node& node) {
    const PlaneMask saved = mask_;
    if (enter(node)) node.traverseCull(*this);
    else node.culledOut(*this);
    mask_ = saved;
}

void CullVisitor::apply(Group& group) {
    const PlaneMask saved = mask_;
    if (enter(group)) traverse(group);
    mask_ = saved;
}

void CullVisitor::apply(Transform& transform) {
    const PlaneMask saved = mask_;
    const Mat4* savedWorld = world_;
    if (enter(transform)) {
        world_ = &transform.worldMatrix();
        traverse(transform);
    }
    world_ = savedWorld;
    mask_ = saved;
}

void CullVisitor::apply(LOD& lod) {
    const PlaneMask saved = mask_;
    if (enter(lod)) {
        // Traditional LOD: this node finds its own centre in world space and its own distance.
        OpTally* ops = nullptr;
        if (counter_) {
            counter_->countOperations(OpCategory::LodDistance);
            ops = counter_->tally(OpCategory::LodDistance);
        }
        const double scaled2 = detail::lodDistanceSquared(*world_, lod.center(), eye_, lodScale2_ * lod.distanceScaleSquared(), ops);
        const int index = lod.selectChildSquared(scaled2, ops);
        ++stats_.lodDistances;
        if (index >= 0) {
            const std::uint32_t savedLevel = lodLevel_;
            lodLevel_ = static_cast<std::uint32_t>(index);
            lod.children()[static_cast<std::size_t>(index)]->accept(*this);
            lodLevel_ = savedLevel;
        }
    }
    mask_ = saved;
}

void CullVisitor::apply(Geometry& geometry) {
    const PlaneMask saved = mask_;
    if (enter(geometry)) {
        const Drawable& drawable = geometry.drawable();
        DrawItem item;
        item.drawable = &drawable;
        item.node = &geometry;
        item.lodLevel = lodLevel_;
        addDrawItem(item, drawable.primitiveCount(), *world_);
    }
    mask_ = saved;
}

}  // namespace throng
