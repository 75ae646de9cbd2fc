#include "throng/actors/TraditionalActorProcessing.h"

#include "ActorDrawItem.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/CullVisitor.h"
#include "throng/scenegraph/FrameContext.h"
#include "throng/scenegraph/MatrixBoundsVisitor.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/scenegraph/Transform.h"

namespace throng {
namespace {

constexpr PlaneMask kCulled = 0xFF;  // marks a node whose subtree sphere was outside

std::span<float> dofsOf(Crowd::State& s, ActorId id) {
    return std::span<float>(s.dofs).subspan(s.dofOffset[id], s.tmpl[id]->dofValueCount());
}

}  // namespace

void traditionalApp(Crowd& crowd, std::span<const ActorId> ids, const FrameContext& context) {
    Crowd::State& s = crowd.state();
    OpCounter* c = context.counter;
    for (ActorId id : ids) {
        Behaviour& b = *s.behaviour[id];
        const std::uint32_t slot = s.slot[id];
        // Every actor, every DOF, at full precision: behaviour does not know what the camera sees.
        s.refLocal[id] = b.referencePoint(slot, context, tallyFor(c, OpCategory::RefpointDofValues));
        s.root[id] = b.skeletonRoot(slot, context.time, 0, tallyFor(c, OpCategory::SkeletonRootDofValues));
        b.pose(slot, context.time, 0, *s.tmpl[id], {}, dofsOf(s, id), tallyFor(c, OpCategory::SkeletonDofValues));
    }
}

BoundingSphere traditionalBound(Crowd& crowd, std::span<const ActorId> ids, MatrixBoundsVisitor& visitor) {
    Crowd::State& s = crowd.state();
    Crowd::TraditionalWorkspace& w = crowd.traditionalWorkspace();
    OpCounter* c = visitor.counter();
    OpTally* refOps = tallyFor(c, OpCategory::RefpointMatrix);
    OpTally* rootOps = tallyFor(c, OpCategory::SkeletonRootMatrix);
    OpTally* nodeOps = tallyFor(c, OpCategory::SkeletonMatrix);
    OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
    MatrixBoundsStatistics& stats = visitor.statistics();
    const Mat4& parent = visitor.parentWorld();
    const bool identity = visitor.parentIsIdentity();
    BoundingSphere bound;
    for (ActorId id : ids) {
        const ActorTemplate& t = *s.tmpl[id];
        const std::size_t n = t.nodeCount();
        const std::uint32_t base = s.nodeOffset[id];
        // Reference Point and Skeleton Root matrices, on the CPU.
        s.refWorld[id] = identity ? s.refLocal[id] : composeAffine(parent, s.refLocal[id], refOps);
        s.sklsWorld[id] = composeAffine(s.refWorld[id], rootPoseMatrix(s.root[id], rootOps), rootOps);
        countOperations(c, OpCategory::RefpointMatrix);
        countOperations(c, OpCategory::SkeletonRootMatrix);
        // Every Skeleton node: local matrix, model matrix and world matrix, on the CPU.
        const std::span<Affine> model(w.model.data() + base, n);
        computeModelTransforms(t, dofsOf(s, id), {}, model, nodeOps);
        for (std::size_t i = 0; i < n; ++i) w.world[base + i] = composeAffine(s.sklsWorld[id], model[i].toDMat4(), nodeOps);
        countOperations(c, OpCategory::SkeletonMatrix, n);
        stats.localMatricesBuilt += n;
        stats.worldMatricesComposed += n + 2;
        // Every internal sphere, bottom-up in world space.
        std::size_t spheres = 0;
        const auto nodes = t.nodes();
        for (std::size_t i = 0; i < n; ++i) {
            const BoundingSphere& local = nodes[i].geometrySphere;
            w.geometry[base + i] = local.valid() ? local.transformed(w.world[base + i], sphereOps) : BoundingSphere();
            spheres += local.valid();
            w.subtree[base + i] = w.geometry[base + i];
        }
        if (s.held[id] >= 0)
            for (const HeldObject& h : s.heldObjects[static_cast<std::size_t>(s.held[id])]) {
                const auto node = base + static_cast<std::uint32_t>(h.node);
                w.subtree[node].expandBy(h.drawable->localBound().transformed(w.world[node], sphereOps), sphereOps);
            }
        BoundingSphere whole = t.rootGeometry().bound().transformed(s.sklsWorld[id], sphereOps);
        for (std::size_t i = n; i-- > 0;) {
            const int p = nodes[i].parent;
            if (p >= 0) w.subtree[base + static_cast<std::size_t>(p)].expandBy(w.subtree[base + i], sphereOps);
            else whole.expandBy(w.subtree[base + i], sphereOps);
        }
        w.whole[id] = whole;
        // Subtree spheres, the Skeleton Root node's and the Reference Point node's.
        spheres += n + 2;
        countOperations(c, OpCategory::BsphereRecompute, spheres);
        stats.spheresRecomputed += spheres;
        bound.expandBy(whole);
    }
    return bound;
}

void traditionalCull(Crowd& crowd, const Node& node, std::span<const ActorId> ids, CullVisitor& visitor, bool testEach) {
    Crowd::State& s = crowd.state();
    Crowd::TraditionalWorkspace& w = crowd.traditionalWorkspace();
    OpCounter* c = visitor.counter();
    OpTally* lodOps = tallyFor(c, OpCategory::LodDistance);
    OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
    CullStatistics& stats = visitor.statistics();
    const Vec3& eye = visitor.eye();
    const double lodScale2 = visitor.lodScaleSquared();
    for (std::uint32_t member = 0; member < ids.size(); ++member) {
        const ActorId id = ids[member];
        const ActorTemplate& t = *s.tmpl[id];
        const std::uint32_t base = s.nodeOffset[id];
        PlaneMask mask = visitor.planeMask();
        // The Reference Point node (tested by the traversal for a lone actor) and the Skeleton Root node.
        if (testEach && visitor.testSphere(w.whole[id], mask) == Containment::Outside) continue;
        if (visitor.testSphere(w.whole[id], mask) == Containment::Outside) continue;
        const Mat4& skls = s.sklsWorld[id];
        auto emit = [&](const Drawable& d, const Mat4* world, std::uint32_t part, int level,
                        const glm::mat4* palette = nullptr, std::size_t paletteSize = 0) {
            visitor.addDrawItem(detail::actorPartItem(&node, member, s.tint[id], d, world, part, level, palette, paletteSize),
                                d.primitiveCount());
        };
        // The actor's own LOD node computes its distance.
        const auto nodes = t.nodes();
        const std::uint32_t n = static_cast<std::uint32_t>(t.nodeCount());
        if (!t.rootGeometry().empty()) {
            const double d2 = detailDistanceSquared(skls, eye, lodScale2, s.priority[id], lodOps);
            countOperations(c, OpCategory::LodDistance);
            ++stats.lodDistances;
            const int level = t.rootGeometry().selectSquared(d2);
            if (level >= 0) {
                const VaLodLevel& lv = t.rootGeometry().levels()[static_cast<std::size_t>(level)];
                PlaneMask leafMask = mask;
                // A skinned mesh moves with its joints: its sphere is theirs, in the current pose.
                if (lv.drawable &&
                    visitor.testSphere(lv.skin >= 0 ? w.whole[id] : lv.drawable->localBound().transformed(skls, sphereOps),
                                       leafMask) != Containment::Outside) {
                    if (lv.skin >= 0) {
                        const Skin& skin = t.skins()[static_cast<std::size_t>(lv.skin)];
                        emit(*lv.drawable, &skls, n, level,
                             detail::skinPaletteOf(crowd, t, skin, std::span<const Affine>(w.model.data() + base, n), {},
                                                   tallyFor(c, OpCategory::SkeletonMatrix)),
                             skin.joints.size());
                    } else {
                        emit(*lv.drawable, &skls, n, level);
                    }
                }
            }
        }
        // Every Skeleton node, depth first; a culled subtree is skipped.
        for (std::uint32_t i = 0; i < n; ++i) {
            const int p = nodes[i].parent;
            PlaneMask nodeMask = p < 0 ? mask : w.masks[static_cast<std::size_t>(p)];
            if (visitor.testSphere(w.subtree[base + i], nodeMask) == Containment::Outside) {
                w.masks[i] = kCulled;
                i = t.subtreeEnd(i) - 1;
                continue;
            }
            w.masks[i] = nodeMask;
            const VaLod& lod = nodes[i].geometry;
            if (!lod.empty()) {
                // Each LOD node computes its own eye distance (NO_05).
                const double d2 = detailDistanceSquared(skls, eye, lodScale2, s.priority[id], lodOps);
                countOperations(c, OpCategory::LodDistance);
                ++stats.lodDistances;
                const int level = lod.selectSquared(d2);
                const auto* drawable = level >= 0 ? lod.levels()[static_cast<std::size_t>(level)].drawable.get() : nullptr;
                PlaneMask leafMask = nodeMask;
                if (drawable && visitor.testSphere(w.geometry[base + i], leafMask) != Containment::Outside &&
                    visitor.testSphere(partWorldSphere(drawable->localBound(), w.model[base + i], skls, sphereOps),
                                       leafMask) != Containment::Outside)
                    emit(*drawable, &w.world[base + i], i, level);
            }
        }
        // Held objects, in their node's frame.
        if (s.held[id] >= 0) {
            const auto& held = s.heldObjects[static_cast<std::size_t>(s.held[id])];
            for (std::uint32_t k = 0; k < held.size(); ++k) {
                const auto holder = static_cast<std::size_t>(held[k].node);
                bool reached = w.masks[holder] != kCulled;
                for (int a = nodes[holder].parent; a >= 0; a = nodes[static_cast<std::size_t>(a)].parent)
                    reached = reached && w.masks[static_cast<std::size_t>(a)] != kCulled;
                if (!reached) continue;
                PlaneMask leafMask = w.masks[holder];
                if (visitor.testSphere(partWorldSphere(held[k].drawable->localBound(), w.model[base + holder], skls, sphereOps),
                                       leafMask) != Containment::Outside)
                    emit(*held[k].drawable, &w.world[base + holder], n + 1 + k, 0);
            }
        }
    }
}

}  // namespace throng
