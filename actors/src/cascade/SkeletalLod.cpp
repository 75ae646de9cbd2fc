// Phase 4 of actor processing, last step (see SkeletalLodJob.h).

#include <algorithm>

#include "throng/actors/SkeletonPose.h"
#include "throng/actors/cascade/SkeletalLodJob.h"

namespace throng::cascade {

const char* SkeletalLodJob::problem() const {
    if (!crowd || !decisions || !posed) return "crowd, decisions and posed are required";
    if (survivors.size() > candidates.size()) return "more survivors than candidates";
    if (decisions->outcome.size() != survivors.size() || decisions->detail2.size() != survivors.size() ||
        decisions->level.size() != survivors.size())
        return "the decisions must have one entry per survivor";
    return nullptr;
}

void SkeletalLodJob::run(PhaseLoop& loop) const {
    throwIfInvalid("SkeletalLodJob", loop.ready() ? problem() : "the loop has no frame");
    const Crowd::State& s = *crowd;
    const SurvivorDecisions& d = *decisions;
    PosedActors& p = *posed;
    // The actors shown, in candidate order; the posed ones get their room in the per-node arrays.
    p.shown.clear();
    p.posedOf.clear();
    p.posed.clear();
    p.level.clear();
    p.nodeBase.clear();
    std::uint32_t nodes = 0;
    for (std::uint32_t k = 0; k < survivors.size(); ++k) {
        if (d.outcome[k] == kRejected) continue;
        p.shown.push_back(k);
        if (d.outcome[k] == kImpostor || d.outcome[k] == kCached) {
            p.posedOf.push_back(PosedActors::kNotPosed);
            continue;
        }
        p.posedOf.push_back(static_cast<std::uint32_t>(p.posed.size()));
        p.posed.push_back(k);
        p.level.push_back(d.level[k]);
        p.nodeBase.push_back(nodes);
        nodes += static_cast<std::uint32_t>(s.tmpl[candidates[survivors[k]].id]->nodeCount());
    }
    p.active.resize(nodes);
    p.model.resize(nodes);
    p.evaluated.resize(p.posed.size());

    // Skeletal LOD: which Skeleton nodes each posed actor keeps.
    loop.parallel(p.posed.size(), kLightGrain, [&](ChunkOutput&, std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
            const ActorTemplate& t = *s.tmpl[candidates[survivors[p.posed[j]]].id];
            const std::span<std::uint8_t> active(p.active.data() + p.nodeBase[j], t.nodeCount());
            if (skeletalLod) computeActiveNodes(t, d.detail2[p.posed[j]], active);
            else std::fill(active.begin(), active.end(), std::uint8_t{1});
        }
    });
}

}  // namespace throng::cascade
