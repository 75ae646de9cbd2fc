// Phase 6 of actor processing, CULL 3 (see InternalCullingJob.h).

#include "HeldObjects.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/cascade/InternalCullingJob.h"

namespace throng::cascade {

const char* InternalCullingJob::problem() const {
    if (!crowd || !frustum || !decisions || !posed || !visibility) return "crowd, frustum, decisions, posed and visibility are required";
    if (actorClass.size() != crowd->tmpl.size()) return "actorClass must have one entry per actor";
    if (survivors.size() > candidates.size()) return "more survivors than candidates";
    if (decisions->detail2.size() != survivors.size()) return "the decisions must have one entry per survivor";
    if (posed->nodeBase.size() != posed->posed.size() || posed->model.size() != posed->active.size())
        return "the posed actors' arrays disagree in size";
    return nullptr;
}

void InternalCullingJob::run(PhaseLoop& loop) const {
    throwIfInvalid("InternalCullingJob", loop.ready() ? problem() : "the loop has no frame");
    const Crowd::State& s = *crowd;
    const PosedActors& p = *posed;
    InternalVisibility& v = *visibility;
    const std::size_t nodes = p.active.size();
    v.geometry.resize(nodes);
    v.subtree.resize(nodes);
    v.masks.resize(nodes);
    v.visible.assign(nodes, 0);
    v.visibility.assign(p.posed.size(), kAllVisible);
    v.rootVisible.assign(p.posed.size(), 1);
    loop.parallel(p.posed.size(), kHeavyGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        OpCounter* c = loop.counterOf(out);
        OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
        OpTally* testOps = tallyFor(c, OpCategory::BsphereFrustumTest);
        ActorFrameStatistics& counts = out.counts;
        auto test = [&](const BoundingSphere& sphere, PlaneMask& m) {
            ++counts.spheresTested;
            countOperations(c, OpCategory::BsphereFrustumTest);
            return frustum->classify(sphere, m, testOps) != Containment::Outside;
        };
        for (std::size_t j = begin; j < end; ++j) {
            const Candidate& cand = candidates[survivors[p.posed[j]]];
            const ActorId id = cand.id;
            if (actorClass[id] != ActorClass::C3_1) continue;  // B and C2 are wholly inside
            const ActorTemplate& t = *s.tmpl[id];
            const std::size_t n = t.nodeCount();
            const std::uint32_t base = p.nodeBase[j];
            const std::span<const std::uint8_t> active(p.active.data() + base, n);
            const std::span<const Affine> model(p.model.data() + base, n);
            BoundingSphere whole = computeInternalSpheres(t, model, active, std::span(v.geometry.data() + base, n),
                                                          std::span(v.subtree.data() + base, n), sphereOps);
            std::size_t computed = 1;
            for (std::size_t i = 0; i < n; ++i)
                if (active[i]) computed += 1 + (v.geometry[base + i].valid() ? 1 : 0);
            if (s.held[id] >= 0)
                for (const HeldObject& h : s.heldObjects[static_cast<std::size_t>(s.held[id])]) {
                    const int holder = holderNode(t, active, h.node);
                    const BoundingSphere sphere =
                        holder < 0 ? h.drawable->localBound()
                                   : h.drawable->localBound().transformed(model[static_cast<std::size_t>(holder)].toDMat4(), sphereOps);
                    for (int a = holder; a >= 0; a = t.nodes()[static_cast<std::size_t>(a)].parent)
                        v.subtree[base + static_cast<std::size_t>(a)].expandBy(sphere, sphereOps);
                    whole.expandBy(sphere, sphereOps);
                }
            countOperations(c, OpCategory::BsphereRecompute, computed);
            counts.internalSpheresComputed += computed;
            const Mat4& skls = s.sklsWorld[id];
            PlaneMask mask = cand.mask;
            ++counts.spheresTested;
            countOperations(c, OpCategory::BsphereFrustumTest);
            const Containment r = frustum->classify(whole.transformed(skls, sphereOps), mask, testOps);
            if (r != Containment::Intersects) {
                v.visibility[j] = r == Containment::Inside ? kAllVisible : kNoneVisible;
                ++counts.c3_1;
                continue;
            }
            actorClass[id] = ActorClass::C3_2;
            ++counts.c3_2;
            v.visibility[j] = kPerPart;
            // The actor-level geometry, then each active node depth first, as traditional CULL does.
            const double d2 = decisions->detail2[p.posed[j]];
            const int rootLevel = t.rootGeometry().selectSquared(d2);
            if (rootLevel >= 0) {
                const VaLodLevel& lv = t.rootGeometry().levels()[static_cast<std::size_t>(rootLevel)];
                PlaneMask m = mask;
                // A skinned mesh's sphere is its joints' (the whole internal bound just found crossing).
                v.rootVisible[j] = lv.drawable && (lv.skin >= 0 || test(lv.drawable->localBound().transformed(skls, sphereOps), m));
            }
            const auto tnodes = t.nodes();
            for (std::size_t i = 0; i < n; ++i) {
                if (!active[i]) {
                    i = t.subtreeEnd(i) - 1;
                    continue;
                }
                const int parent = tnodes[i].parent;
                PlaneMask m = parent < 0 ? mask : v.masks[base + static_cast<std::size_t>(parent)];
                if (!test(v.subtree[base + i].transformed(skls, sphereOps), m)) {
                    v.masks[base + i] = kCulled;
                    for (std::size_t k = i; k < t.subtreeEnd(i); ++k) v.visible[base + k] = 0;
                    i = t.subtreeEnd(i) - 1;
                    continue;
                }
                v.masks[base + i] = m;
                const VaLod& lod = tnodes[i].geometry;
                const int level = lod.selectSquared(d2);
                const auto* drawable = level >= 0 ? lod.levels()[static_cast<std::size_t>(level)].drawable.get() : nullptr;
                PlaneMask leaf = m;
                v.visible[base + i] = drawable && v.geometry[base + i].valid() &&
                                      test(v.geometry[base + i].transformed(skls, sphereOps), leaf) &&
                                      test(partWorldSphere(drawable->localBound(), model[i], skls, sphereOps), leaf);
            }
        }
    });
}

}  // namespace throng::cascade
