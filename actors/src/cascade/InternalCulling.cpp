// Phase 6 of actor processing, CULL 3: hierarchical internal bounding spheres, only for actors whose
// Sklsroot Bsphere crosses a plane (C3). The whole internal bound decides first (C3.1: wholly in or
// out); otherwise (C3.2) the actor-level geometry and each active node are tested depth first with
// plane masks, as traditional CULL tests them.

#include "CascadeFrame.h"
#include "HeldObjects.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/SkeletonPose.h"

namespace throng::cascade {

void cullInternalSpheres(CascadeFrame& f) {
    Crowd::State& s = f.crowd->state();
    const std::size_t nodes = f.active.size();
    f.geometry.resize(nodes);
    f.subtree.resize(nodes);
    f.masks.resize(nodes);
    f.visible.assign(nodes, 0);
    f.visibility.assign(f.posed.size(), kAllVisible);
    f.rootVisible.assign(f.posed.size(), 1);
    const Frustum& frustum = f.frustum;
    f.parallel(f.posed.size(), kHeavyGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        OpCounter* c = f.counterOf(out);
        OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
        OpTally* testOps = tallyFor(c, OpCategory::BsphereFrustumTest);
        ActorFrameStatistics& counts = out.counts;
        auto test = [&](const BoundingSphere& sphere, PlaneMask& m) {
            ++counts.spheresTested;
            countOperations(c, OpCategory::BsphereFrustumTest);
            return frustum.classify(sphere, m, testOps) != Containment::Outside;
        };
        for (std::size_t j = begin; j < end; ++j) {
            const Candidate& cand = f.candidates[f.survivors[f.posed[j]]];
            const ActorId id = cand.id;
            if (s.actorClass[id] != ActorClass::C3_1) continue;  // B and C2 are wholly inside
            const ActorTemplate& t = *s.tmpl[id];
            const std::size_t n = t.nodeCount();
            const std::uint32_t base = f.nodeBase[j];
            const std::span<const std::uint8_t> active(f.active.data() + base, n);
            const std::span<const Affine> model(f.model.data() + base, n);
            BoundingSphere whole = computeInternalSpheres(t, model, active, std::span(f.geometry.data() + base, n),
                                                          std::span(f.subtree.data() + base, n), sphereOps);
            std::size_t computed = 1;
            for (std::size_t i = 0; i < n; ++i)
                if (active[i]) computed += 1 + (f.geometry[base + i].valid() ? 1 : 0);
            if (s.held[id] >= 0)
                for (const HeldObject& h : s.heldObjects[static_cast<std::size_t>(s.held[id])]) {
                    const int holder = holderNode(t, active, h.node);
                    const BoundingSphere sphere =
                        holder < 0 ? h.drawable->localBound()
                                   : h.drawable->localBound().transformed(model[static_cast<std::size_t>(holder)].toDMat4(), sphereOps);
                    for (int a = holder; a >= 0; a = t.nodes()[static_cast<std::size_t>(a)].parent)
                        f.subtree[base + static_cast<std::size_t>(a)].expandBy(sphere, sphereOps);
                    whole.expandBy(sphere, sphereOps);
                }
            countOperations(c, OpCategory::BsphereRecompute, computed);
            counts.internalSpheresComputed += computed;
            const Mat4& skls = s.sklsWorld[id];
            PlaneMask mask = cand.mask;
            ++counts.spheresTested;
            countOperations(c, OpCategory::BsphereFrustumTest);
            const Containment r = frustum.classify(whole.transformed(skls, sphereOps), mask, testOps);
            if (r != Containment::Intersects) {
                f.visibility[j] = r == Containment::Inside ? kAllVisible : kNoneVisible;
                ++counts.c3_1;
                continue;
            }
            s.actorClass[id] = ActorClass::C3_2;
            ++counts.c3_2;
            f.visibility[j] = kPerPart;
            // The actor-level geometry, then each active node depth first, as traditional CULL does.
            const double d2 = f.detail2[f.posed[j]];
            const int rootLevel = t.rootGeometry().selectSquared(d2);
            if (rootLevel >= 0) {
                const VaLodLevel& lv = t.rootGeometry().levels()[static_cast<std::size_t>(rootLevel)];
                PlaneMask m = mask;
                // A skinned mesh's sphere is its joints' (the whole internal bound just found crossing).
                f.rootVisible[j] = lv.drawable && (lv.skin >= 0 || test(lv.drawable->localBound().transformed(skls, sphereOps), m));
            }
            const auto tnodes = t.nodes();
            for (std::size_t i = 0; i < n; ++i) {
                if (!active[i]) {
                    i = t.subtreeEnd(i) - 1;
                    continue;
                }
                const int p = tnodes[i].parent;
                PlaneMask m = p < 0 ? mask : f.masks[base + static_cast<std::size_t>(p)];
                if (!test(f.subtree[base + i].transformed(skls, sphereOps), m)) {
                    f.masks[base + i] = kCulled;
                    for (std::size_t k = i; k < t.subtreeEnd(i); ++k) f.visible[base + k] = 0;
                    i = t.subtreeEnd(i) - 1;
                    continue;
                }
                f.masks[base + i] = m;
                const VaLod& lod = tnodes[i].geometry;
                const int level = lod.selectSquared(d2);
                const auto* drawable = level >= 0 ? lod.levels()[static_cast<std::size_t>(level)].drawable.get() : nullptr;
                PlaneMask leaf = m;
                f.visible[base + i] = drawable && f.geometry[base + i].valid() &&
                                      test(f.geometry[base + i].transformed(skls, sphereOps), leaf) &&
                                      test(partWorldSphere(drawable->localBound(), model[i], skls, sphereOps), leaf);
            }
        }
    });
}

}  // namespace throng::cascade
