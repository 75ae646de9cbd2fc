// Phase 2 of actor processing, CULL 1: Refpoint Bspheres against the frustum. A lone actor's and a
// group's sphere were tested by the generic CULL traversal; members of groups that cross a plane are
// tested here, flat and several at a time, relative to the eye. Members another process simulates
// and did not send (not present()) were found outside the view there.

#include "CascadeFrame.h"
#include "throng/actors/Crowd.h"
#include "throng/scenegraph/SphereArrayCuller.h"

namespace throng::cascade {

void cullReferencePoints(CascadeFrame& f) {
    const Crowd::State& s = f.crowd->state();
    f.pending.clear();
    f.cx.clear(), f.cy.clear(), f.cz.clear(), f.cr.clear();
    for (std::uint32_t k = 0; k < f.candidates.size(); ++k) {
        const Candidate& c = f.candidates[k];
        if (c.stage != kPending) continue;
        const BoundingSphere& b = s.refSphereWorld[c.id];
        const Vec3 rel = b.center() - f.eye;
        f.pending.push_back(k);
        f.cx.push_back(static_cast<float>(rel.x));
        f.cy.push_back(static_cast<float>(rel.y));
        f.cz.push_back(static_cast<float>(rel.z));
        f.cr.push_back(static_cast<float>(b.radius()));
    }
    f.containment.resize(f.pending.size());
    const SphereArrayCuller culler(f.frustum, f.eye);
    f.parallel(f.pending.size(), 4 * kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        const std::size_t n = end - begin;
        const SphereArrays spheres{std::span<const float>(f.cx).subspan(begin, n), std::span<const float>(f.cy).subspan(begin, n),
                                   std::span<const float>(f.cz).subspan(begin, n), std::span<const float>(f.cr).subspan(begin, n)};
        OpCounter* c = f.counterOf(out);
        culler.classify(spheres, std::span<Containment>(f.containment).subspan(begin, n), tallyFor(c, OpCategory::BsphereFrustumTest));
        countOperations(c, OpCategory::BsphereFrustumTest, n);
        out.counts.spheresTested += n;
    });
    for (std::size_t i = 0; i < f.pending.size(); ++i) {
        Candidate& cand = f.candidates[f.pending[i]];
        // An actor simulated by another process that did not send it this step lies outside the
        // view (that is why it was not sent); its state here is stale, so its test decides nothing.
        if (!s.behaviour[cand.id]->present(s.slot[cand.id])) f.containment[i] = Containment::Outside;
        switch (f.containment[i]) {
            case Containment::Outside: cand.stage = kOutside; break;
            case Containment::Inside: cand.stage = kInside, cand.mask = 0; break;
            case Containment::Intersects: cand.stage = kCrossing; break;
        }
    }

    Crowd::State& state = f.crowd->state();
    f.survivors.clear();
    for (std::uint32_t k = 0; k < f.candidates.size(); ++k) {
        const Candidate& cand = f.candidates[k];
        if (cand.stage == kOutside) {
            state.actorClass[cand.id] = ActorClass::A;
            ++f.stats->a;
        } else {
            f.survivors.push_back(k);
        }
    }
}

}  // namespace throng::cascade
