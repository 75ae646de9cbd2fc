// Phase 5 of actor processing (see BehavioursJob.h).

#include "throng/actors/SkeletonPose.h"
#include "throng/actors/cascade/BehavioursJob.h"

namespace throng::cascade {

const char* BehavioursJob::problem() const {
    if (!crowd || !posed) return "crowd and posed are required";
    if (dofs.size() != crowd->dofs.size()) return "dofs must hold every actor's DOF values";
    if (survivors.size() > candidates.size()) return "more survivors than candidates";
    const PosedActors& p = *posed;
    if (p.level.size() != p.posed.size() || p.nodeBase.size() != p.posed.size() || p.evaluated.size() != p.posed.size())
        return "level, nodeBase and evaluated must have one entry per posed actor";
    if (p.model.size() != p.active.size()) return "model must have one entry per node";
    return nullptr;
}

void BehavioursJob::run(PhaseLoop& loop) const {
    throwIfInvalid("BehavioursJob", loop.ready() ? problem() : "the loop has no frame");
    const Crowd::State& s = *crowd;
    PosedActors& p = *posed;
    loop.parallel(p.posed.size(), kHeavyGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        OpCounter* c = loop.counterOf(out);
        OpTally* nodeOps = tallyFor(c, OpCategory::SkeletonMatrix);
        OpTally* valueOps = tallyFor(c, OpCategory::SkeletonDofValues);
        auto idOf = [&](std::size_t j) { return candidates[survivors[p.posed[j]]].id; };
        for (std::size_t j = begin; j < end; ++j) {
            const ActorId id = idOf(j);
            const ActorTemplate& t = *s.tmpl[id];
            const std::span<const std::uint8_t> active(p.active.data() + p.nodeBase[j], t.nodeCount());
            s.behaviour[id]->pose(s.slot[id], time, p.level[j], t, active, dofs.subspan(s.dofOffset[id], t.dofValueCount()), valueOps);
        }
        // Model transforms, up to kPoseLanes consecutive actors of one template at a time.
        detail::poseInBatches(
            begin, end, [&](std::size_t j) -> const ActorTemplate& { return *s.tmpl[idOf(j)]; },
            [&](std::size_t j) {
                return detail::PoseLane{dofs.data() + s.dofOffset[idOf(j)], p.active.data() + p.nodeBase[j], p.model.data() + p.nodeBase[j]};
            },
            out.pose, nodeOps,
            [&](std::size_t j, std::uint32_t evaluated) {
                p.evaluated[j] = evaluated;
                countOperations(c, OpCategory::SkeletonMatrix, evaluated);
                out.counts.skeletonNodesEvaluated += evaluated;
            });
    });
    loop.statistics().actorsPosed = p.posed.size();
}

}  // namespace throng::cascade
