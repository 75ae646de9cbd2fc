#include "throng/actors/TraditionalActorProcessing.h"

#include "ActorDrawItem.h"
#include "ReferencePointRuns.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/detail/PoseBatch.h"
#include "throng/actors/detail/PoseKernels.h"
#include "throng/scenegraph/CullVisitor.h"
#include "throng/scenegraph/FrameContext.h"
#include "throng/scenegraph/MatrixBoundsVisitor.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/scenegraph/Transform.h"

namespace throng {
namespace {

constexpr PlaneMask kCulled = 0xFF;  // marks a node whose subtree sphere was outside
constexpr std::size_t kGrain = 64;   // actors per chunk of the parallel loops

using Chunk = Crowd::TraditionalWorkspace::Chunk;

std::span<float> dofsOf(Crowd::State& s, ActorId id) {
    return std::span<float>(s.dofs).subspan(s.dofOffset[id], s.tmpl[id]->dofValueCount());
}

// Runs body(chunk, begin, end) over [0, n) in fixed chunks, each with fresh outputs (its counter
// enabled when `counting`; with `cull`, a segment of its draw list of its own, in chunk order), and
// returns the number of chunks, whose outputs the caller joins in order.
template <class Body>
std::size_t inChunks(Crowd& crowd, std::size_t n, bool counting, CullVisitor* cull, Body&& body) {
    auto& chunks = crowd.traditionalWorkspace().chunks;
    const std::size_t count = chunkCount(n, kGrain);
    if (chunks.size() < count) chunks.resize(count);
    const std::size_t first = cull ? cull->openDrawSegments(count) : 0;
    for (std::size_t c = 0; c < count; ++c) {
        Chunk& out = chunks[c];
        out.ops.reset();
        out.ops.setEnabled(counting);
        out.items = cull ? &cull->drawSegment(first + c) : nullptr;
        out.bound = BoundingSphere();
        out.matrices = {};
        out.spheresTested = out.lodDistances = 0;
    }
    forEachChunk(n, kGrain, [&](std::size_t c, std::size_t begin, std::size_t end) { body(chunks[c], begin, end); });
    return count;
}

// The sphere test of CullVisitor::testSphere, accounted in a chunk.
Containment testSphere(const Frustum& frustum, const BoundingSphere& sphere, PlaneMask& mask, Chunk& out, OpCounter* c) {
    if (!sphere.valid()) return Containment::Outside;
    if (mask == 0) return Containment::Inside;  // an ancestor is inside every plane
    ++out.spheresTested;
    countOperations(c, OpCategory::BsphereFrustumTest);
    return frustum.classify(sphere, mask, tallyFor(c, OpCategory::BsphereFrustumTest));
}

// Every actor, every DOF, at full precision: behaviour does not know what the camera sees (the
// Reference Point came before, with its neighbours').
void appOne(Crowd::State& s, ActorId id, const FrameContext& context) {
    OpCounter* c = context.counter;
    Behaviour& b = *s.behaviour[id];
    const std::uint32_t slot = s.slot[id];
    s.root[id] = b.skeletonRoot(slot, context.time, 0, tallyFor(c, OpCategory::SkeletonRootDofValues));
    b.pose(slot, context.time, 0, *s.tmpl[id], {}, dofsOf(s, id), tallyFor(c, OpCategory::SkeletonDofValues));
}

// Model transforms of every node of the actors ids[begin, end), up to kPoseLanes consecutive actors
// of one template at a time (the pose job actor processing runs, on every node).
void poseModels(Crowd::State& s, Crowd::TraditionalWorkspace& w, std::span<const ActorId> ids, std::size_t begin,
                std::size_t end, Chunk& out, OpCounter* c) {
    detail::poseInBatches(
        begin, end, [&](std::size_t k) -> const ActorTemplate& { return *s.tmpl[ids[k]]; },
        [&](std::size_t k) {
            return detail::PoseLane{s.dofs.data() + s.dofOffset[ids[k]], nullptr, w.model.data() + s.nodeOffset[ids[k]]};
        },
        out.pose, tallyFor(c, OpCategory::SkeletonMatrix), [](std::size_t, std::uint32_t) {});
}

// Matrices and spheres of one actor under `parent`, all on the CPU, its model transforms posed
// (poseModels); returns its whole bound.
BoundingSphere boundOne(Crowd::State& s, Crowd::TraditionalWorkspace& w, ActorId id, const Mat4& parent, bool identity,
                        Chunk& out, OpCounter* c) {
    OpTally* refOps = tallyFor(c, OpCategory::RefpointMatrix);
    OpTally* rootOps = tallyFor(c, OpCategory::SkeletonRootMatrix);
    OpTally* nodeOps = tallyFor(c, OpCategory::SkeletonMatrix);
    OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
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
    for (std::size_t i = 0; i < n; ++i) detail::nodeWorldMatrix<float>(s.sklsWorld[id], model[i], w.world[base + i], nodeOps);
    countOperations(c, OpCategory::SkeletonMatrix, n);
    out.matrices.localMatricesBuilt += n;
    out.matrices.worldMatricesComposed += n + 2;
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
    out.matrices.spheresRecomputed += spheres;
    return whole;
}

// CULL of one actor, member `member` of `node`, as a generic scenegraph would do it.
void cullOne(Crowd::State& s, Crowd::TraditionalWorkspace& w, const Node& node, std::uint32_t member, ActorId id,
             const CullVisitor& visitor, bool testEach, Chunk& out, OpCounter* c, double time) {
    OpTally* lodOps = tallyFor(c, OpCategory::LodDistance);
    OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
    const Frustum& frustum = visitor.frustum();
    const Vec3& eye = visitor.eye();
    const double lodScale2 = visitor.lodScaleSquared();
    const ActorTemplate& t = *s.tmpl[id];
    const std::uint32_t base = s.nodeOffset[id];
    PlaneMask mask = visitor.planeMask();
    // The Reference Point node (tested by the traversal for a lone actor) and the Skeleton Root node.
    if (testEach && testSphere(frustum, w.whole[id], mask, out, c) == Containment::Outside) return;
    if (testSphere(frustum, w.whole[id], mask, out, c) == Containment::Outside) return;
    const Mat4& skls = s.sklsWorld[id];
    const detail::ActorItemBase a = detail::actorItemBase(s, id, &node, member, time);
    // Items are written in place, each with its own transform (the list must outlive the workspace).
    auto emit = [&](const Drawable& d, const Mat4& world, std::uint32_t part, int level, std::size_t paletteSize = 0) -> DrawItem& {
        DrawItem& item = detail::addActorPart(*out.items, a, d, part, level, paletteSize);
        item.world = ItemTransform(world);
        return item;
    };
    const auto nodes = t.nodes();
    const std::uint32_t n = static_cast<std::uint32_t>(t.nodeCount());
    if (out.masks.size() < n) out.masks.resize(n);
    // The actor's own LOD node computes its distance.
    if (!t.rootGeometry().empty()) {
        const double d2 = detailDistanceSquared(skls, eye, lodScale2, s.priority[id], lodOps);
        countOperations(c, OpCategory::LodDistance);
        ++out.lodDistances;
        const int level = t.rootGeometry().selectSquared(d2);
        if (level >= 0) {
            const VaLodLevel& lv = t.rootGeometry().levels()[static_cast<std::size_t>(level)];
            PlaneMask leafMask = mask;
            // A skinned mesh moves with its joints: its sphere is theirs, in the current pose.
            if (lv.drawable &&
                testSphere(frustum, lv.skin >= 0 ? w.whole[id] : lv.drawable->localBound().transformed(skls, sphereOps), leafMask,
                           out, c) != Containment::Outside) {
                if (lv.skin >= 0) {
                    const Skin& skin = t.skins()[static_cast<std::size_t>(lv.skin)];
                    DrawItem& item = emit(*lv.drawable, skls, n, level, skin.joints.size());
                    computeSkinPalette(t, skin, std::span<const Affine>(w.model.data() + base, n), {}, DrawSegment::paletteRoom(item),
                                       tallyFor(c, OpCategory::SkeletonMatrix));
                } else {
                    emit(*lv.drawable, skls, n, level);
                }
            }
        }
    }
    // Every Skeleton node, depth first; a culled subtree is skipped.
    for (std::uint32_t i = 0; i < n; ++i) {
        const int p = nodes[i].parent;
        PlaneMask nodeMask = p < 0 ? mask : out.masks[static_cast<std::size_t>(p)];
        if (testSphere(frustum, w.subtree[base + i], nodeMask, out, c) == Containment::Outside) {
            out.masks[i] = kCulled;
            i = t.subtreeEnd(i) - 1;
            continue;
        }
        out.masks[i] = nodeMask;
        const VaLod& lod = nodes[i].geometry;
        if (lod.empty()) continue;
        // Each LOD node computes its own eye distance (NO_05).
        const double d2 = detailDistanceSquared(skls, eye, lodScale2, s.priority[id], lodOps);
        countOperations(c, OpCategory::LodDistance);
        ++out.lodDistances;
        const int level = lod.selectSquared(d2);
        const auto* drawable = level >= 0 ? lod.levels()[static_cast<std::size_t>(level)].drawable.get() : nullptr;
        PlaneMask leafMask = nodeMask;
        if (drawable && testSphere(frustum, w.geometry[base + i], leafMask, out, c) != Containment::Outside &&
            testSphere(frustum, partWorldSphere(drawable->localBound(), w.model[base + i], skls, sphereOps), leafMask, out, c) !=
                Containment::Outside)
            emit(*drawable, w.world[base + i], i, level);
    }
    // Held objects, in their node's frame.
    if (s.held[id] < 0) return;
    const auto& held = s.heldObjects[static_cast<std::size_t>(s.held[id])];
    for (std::uint32_t k = 0; k < held.size(); ++k) {
        const auto holder = static_cast<std::size_t>(held[k].node);
        bool reached = out.masks[holder] != kCulled;
        for (int p = nodes[holder].parent; p >= 0; p = nodes[static_cast<std::size_t>(p)].parent)
            reached = reached && out.masks[static_cast<std::size_t>(p)] != kCulled;
        if (!reached) continue;
        PlaneMask leafMask = out.masks[holder];
        if (testSphere(frustum, partWorldSphere(held[k].drawable->localBound(), w.model[base + holder], skls, sphereOps), leafMask,
                       out, c) != Containment::Outside)
            emit(*held[k].drawable, w.world[base + holder], n + 1 + k, 0);
    }
}

}  // namespace

void traditionalApp(Crowd& crowd, std::span<const ActorId> ids, const FrameContext& context) {
    crowd.writeAllStates();  // it reads every actor it is given
    Crowd::State& s = crowd.state();
    const std::size_t chunks = inChunks(crowd, ids.size(), context.counter != nullptr, nullptr, [&](Chunk& out, std::size_t begin, std::size_t end) {
        FrameContext local = context;
        local.counter = context.counter ? &out.ops : nullptr;
        detail::computeReferencePointRuns(s, begin, end, [&](std::size_t k) { return ids[k]; }, local,
                                          tallyFor(local.counter, OpCategory::RefpointDofValues));
        for (std::size_t k = begin; k < end; ++k) appOne(s, ids[k], local);
    });
    if (context.counter)
        for (std::size_t c = 0; c < chunks; ++c) context.counter->add(crowd.traditionalWorkspace().chunks[c].ops);
}

BoundingSphere traditionalBound(Crowd& crowd, std::span<const ActorId> ids, MatrixBoundsVisitor& visitor) {
    Crowd::State& s = crowd.state();
    Crowd::TraditionalWorkspace& w = crowd.traditionalWorkspace();
    OpCounter* counter = visitor.counter();
    const Mat4& parent = visitor.parentWorld();
    const bool identity = visitor.parentIsIdentity();
    const std::size_t chunks = inChunks(crowd, ids.size(), counter != nullptr, nullptr, [&](Chunk& out, std::size_t begin, std::size_t end) {
        OpCounter* c = counter ? &out.ops : nullptr;
        poseModels(s, w, ids, begin, end, out, c);
        for (std::size_t k = begin; k < end; ++k) out.bound.expandBy(boundOne(s, w, ids[k], parent, identity, out, c));
    });
    BoundingSphere bound;
    MatrixBoundsStatistics& stats = visitor.statistics();
    for (std::size_t c = 0; c < chunks; ++c) {
        const Chunk& out = w.chunks[c];
        bound.expandBy(out.bound);
        stats.localMatricesBuilt += out.matrices.localMatricesBuilt;
        stats.worldMatricesComposed += out.matrices.worldMatricesComposed;
        stats.spheresRecomputed += out.matrices.spheresRecomputed;
        if (counter) counter->add(out.ops);
    }
    return bound;
}

void traditionalCull(Crowd& crowd, const Node& node, std::span<const ActorId> ids, CullVisitor& visitor, bool testEach) {
    Crowd::State& s = crowd.state();
    Crowd::TraditionalWorkspace& w = crowd.traditionalWorkspace();
    OpCounter* counter = visitor.counter();
    const double time = visitor.frameTime();
    const std::size_t chunks = inChunks(crowd, ids.size(), counter != nullptr, &visitor, [&](Chunk& out, std::size_t begin, std::size_t end) {
        OpCounter* c = counter ? &out.ops : nullptr;
        for (std::size_t k = begin; k < end; ++k)
            cullOne(s, w, node, static_cast<std::uint32_t>(k), ids[k], visitor, testEach, out, c, time);
    });
    CullStatistics& stats = visitor.statistics();
    for (std::size_t c = 0; c < chunks; ++c) {
        Chunk& out = w.chunks[c];
        stats.drawItems += out.items->size();
        stats.primitives += out.items->primitiveCount();
        stats.spheresTested += out.spheresTested;
        stats.lodDistances += out.lodDistances;
        if (counter) counter->add(out.ops);
    }
}

}  // namespace throng
