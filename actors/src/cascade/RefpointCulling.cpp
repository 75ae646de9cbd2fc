// Phase 2 of actor processing, CULL 1 (see RefpointCullingJob.h).

#include "throng/actors/cascade/RefpointCullingJob.h"
#include "throng/scenegraph/SphereArrayCuller.h"

namespace throng::cascade {

const char* RefpointCullingJob::problem() const {
    if (!crowd || !frustum || !survivors || !scratch) return "crowd, frustum, survivors and scratch are required";
    if (actorClass.size() != crowd->tmpl.size()) return "actorClass must have one entry per actor";
    return nullptr;
}

void RefpointCullingJob::run(PhaseLoop& loop) const {
    throwIfInvalid("RefpointCullingJob", loop.ready() ? problem() : "the loop has no frame");
    const Crowd::State& s = *crowd;
    Scratch& w = *scratch;
    w.pending.clear();
    w.cx.clear(), w.cy.clear(), w.cz.clear(), w.cr.clear();
    for (std::uint32_t k = 0; k < candidates.size(); ++k) {
        const Candidate& c = candidates[k];
        if (c.stage != kPending) continue;
        const BoundingSphere& b = s.refSphereWorld[c.id];
        const Vec3 rel = b.center() - eye;
        w.pending.push_back(k);
        w.cx.push_back(static_cast<float>(rel.x));
        w.cy.push_back(static_cast<float>(rel.y));
        w.cz.push_back(static_cast<float>(rel.z));
        w.cr.push_back(static_cast<float>(b.radius()));
    }
    w.containment.resize(w.pending.size());
    const SphereArrayCuller culler(*frustum, eye);
    loop.parallel(w.pending.size(), 4 * kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        const std::size_t n = end - begin;
        const SphereArrays spheres{std::span<const float>(w.cx).subspan(begin, n), std::span<const float>(w.cy).subspan(begin, n),
                                   std::span<const float>(w.cz).subspan(begin, n), std::span<const float>(w.cr).subspan(begin, n)};
        OpCounter* c = loop.counterOf(out);
        culler.classify(spheres, std::span<Containment>(w.containment).subspan(begin, n), tallyFor(c, OpCategory::BsphereFrustumTest));
        countOperations(c, OpCategory::BsphereFrustumTest, n);
        out.counts.spheresTested += n;
    });
    for (std::size_t i = 0; i < w.pending.size(); ++i) {
        Candidate& cand = candidates[w.pending[i]];
        switch (w.containment[i]) {
            case Containment::Outside: cand.stage = kOutside; break;
            case Containment::Inside: cand.stage = kInside, cand.mask = 0; break;
            case Containment::Intersects: cand.stage = kCrossing; break;
        }
    }

    survivors->clear();
    for (std::uint32_t k = 0; k < candidates.size(); ++k) {
        const Candidate& cand = candidates[k];
        if (cand.stage == kOutside) {
            actorClass[cand.id] = ActorClass::A;
            ++loop.statistics().a;
        } else {
            survivors->push_back(k);
        }
    }
}

}  // namespace throng::cascade
