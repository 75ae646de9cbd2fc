#include "throng/actors/SkeletonPose.h"

#include <algorithm>

#include "SpanChecks.h"
#include "throng/actors/detail/PoseKernels.h"

namespace throng {

std::size_t computeActiveNodes(const ActorTemplate& tmpl, double distance2, std::span<std::uint8_t> active) {
    detail::requireEntries(active.size(), tmpl.nodeCount(), "computeActiveNodes", "active", tmpl, "one flag per node");
    const auto nodes = tmpl.nodes();
    std::size_t count = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const int p = nodes[i].parent;
        const bool parentActive = p < 0 || active[static_cast<std::size_t>(p)];
        const double d = nodes[i].deactivationDistance;
        const bool on = parentActive && distance2 < d * d;
        active[i] = on ? 1 : 0;
        count += on;
    }
    return count;
}

void computeSkinPalette(const ActorTemplate& tmpl, const Skin& skin, std::span<const Affine> model,
                        std::span<const std::uint8_t> active, std::span<glm::mat4> palette, OpTally* ops) {
    constexpr const char* where = "computeSkinPalette";
    detail::requireEntries(model.size(), tmpl.nodeCount(), where, "model", tmpl, "one transform per node");
    detail::requireFlagsOrNone(active.size(), tmpl.nodeCount(), where, tmpl);
    detail::requireEntries(palette.size(), skin.joints.size(), where, "palette", tmpl, "one matrix per joint of the skin");
    detail::computeSkinPalette(tmpl, skin, model, active, palette, ops);
}

double detailDistanceSquared(const Mat4& skeletonRootWorld, const Vec3& eye, double lodScale2, float priority,
                             OpTally* ops) {
    return detail::detailDistanceSquared(skeletonRootWorld, eye, lodScale2, static_cast<double>(priority), ops);
}

double eyeDistance(const Mat4& skeletonRootWorld, const Vec3& eye, OpTally* ops) {
    return detail::eyeDistance(skeletonRootWorld, eye, ops);
}

Mat4 rootPoseMatrix(const RootPose& root, OpTally* ops) { return detail::rootPoseMatrix(root, ops); }

void nodeWorldMatrix(const Mat4& skeletonRootWorld, const Affine& model, Mat4& world, OpTally* ops) {
    detail::nodeWorldMatrix(skeletonRootWorld, model, world, ops);
}

BoundingSphere partWorldSphere(const BoundingSphere& local, const Affine& model, const Mat4& skeletonRootWorld,
                               OpTally* ops) {
    return detail::partWorldSphere(local, model, skeletonRootWorld, ops);
}

void writeRestPose(const ActorTemplate& tmpl, std::span<const std::uint8_t> active, std::span<float> dofs) {
    detail::requireFlagsOrNone(active.size(), tmpl.nodeCount(), "writeRestPose", tmpl);
    detail::requireEntries(dofs.size(), tmpl.dofValueCount(), "writeRestPose", "dofs", tmpl, "every DOF value");
    const auto rest = tmpl.restDofs();
    for (std::size_t i = 0; i < tmpl.nodeCount(); ++i) {
        if (!active.empty() && !active[i]) continue;
        const std::uint32_t begin = tmpl.dofOffset(i);
        const std::uint32_t end = i + 1 < tmpl.nodeCount() ? tmpl.dofOffset(i + 1) : tmpl.dofValueCount();
        std::copy(rest.begin() + begin, rest.begin() + end, dofs.begin() + begin);
    }
}

Affine nodeLocalTransform(const SkeletonNode& node, const float* values, OpTally* ops) {
    return detail::nodeLocalTransform(node, values, ops);
}

std::size_t computeModelTransforms(const ActorTemplate& tmpl, std::span<const float> dofs,
                                   std::span<const std::uint8_t> active, std::span<Affine> model, OpTally* ops) {
    constexpr const char* where = "computeModelTransforms";
    detail::requireEntries(dofs.size(), tmpl.dofValueCount(), where, "dofs", tmpl, "every DOF value");
    detail::requireFlagsOrNone(active.size(), tmpl.nodeCount(), where, tmpl);
    detail::requireEntries(model.size(), tmpl.nodeCount(), where, "model", tmpl, "one transform per node");
    return detail::computeModelTransforms(tmpl, dofs, active, model, ops);
}

BoundingSphere computeInternalSpheres(const ActorTemplate& tmpl, std::span<const Affine> model,
                                      std::span<const std::uint8_t> active, std::span<BoundingSphere> geometry,
                                      std::span<BoundingSphere> subtree, OpTally* ops) {
    constexpr const char* where = "computeInternalSpheres";
    detail::requireEntries(model.size(), tmpl.nodeCount(), where, "model", tmpl, "one transform per node");
    detail::requireFlagsOrNone(active.size(), tmpl.nodeCount(), where, tmpl);
    detail::requireEntries(geometry.size(), tmpl.nodeCount(), where, "geometry", tmpl, "one sphere per node");
    detail::requireEntries(subtree.size(), tmpl.nodeCount(), where, "subtree", tmpl, "one sphere per node");
    return detail::computeInternalSpheres(tmpl, model, active, geometry, subtree, ops);
}

}  // namespace throng
