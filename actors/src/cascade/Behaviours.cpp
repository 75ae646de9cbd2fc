// Phase 5 of actor processing: each posed actor's behaviour writes the DOF values of its active
// Skeleton nodes at its behavioural level; their model matrices follow.

#include "CascadeFrame.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/SkeletonPose.h"

namespace throng::cascade {

void evaluateBehaviours(CascadeFrame& f) {
    Crowd::State& s = f.crowd->state();
    const double time = f.context.time;
    f.evaluated.resize(f.posed.size());
    f.parallel(f.posed.size(), kHeavyGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        OpCounter* c = f.counterOf(out);
        OpTally* nodeOps = tallyFor(c, OpCategory::SkeletonMatrix);
        OpTally* valueOps = tallyFor(c, OpCategory::SkeletonDofValues);
        auto idOf = [&](std::size_t j) { return f.candidates[f.survivors[f.posed[j]]].id; };
        for (std::size_t j = begin; j < end; ++j) {
            const ActorId id = idOf(j);
            const ActorTemplate& t = *s.tmpl[id];
            const std::span<const std::uint8_t> active(f.active.data() + f.nodeBase[j], t.nodeCount());
            const std::span<float> dofs = std::span<float>(s.dofs).subspan(s.dofOffset[id], t.dofValueCount());
            s.behaviour[id]->pose(s.slot[id], time, f.level[j], t, active, dofs, valueOps);
        }
        // Model transforms, up to kPoseLanes consecutive actors of one template at a time.
        detail::poseInBatches(
            begin, end, [&](std::size_t j) -> const ActorTemplate& { return *s.tmpl[idOf(j)]; },
            [&](std::size_t j) {
                return detail::PoseLane{s.dofs.data() + s.dofOffset[idOf(j)], f.active.data() + f.nodeBase[j],
                                        f.model.data() + f.nodeBase[j]};
            },
            out.pose, nodeOps,
            [&](std::size_t j, std::uint32_t evaluated) {
                f.evaluated[j] = evaluated;
                countOperations(c, OpCategory::SkeletonMatrix, evaluated);
                out.counts.skeletonNodesEvaluated += evaluated;
            });
    });
    f.stats->actorsPosed = f.posed.size();
}

}  // namespace throng::cascade
