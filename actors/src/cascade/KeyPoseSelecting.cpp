// Phase 4 of actor processing, key-pose caches (see KeyPoseSelectingJob.h): Toledo et al.'s greedy
// selection (§4.2) over the demands of the frame.

#include "throng/actors/KeyPoseCache.h"
#include "throng/actors/cascade/KeyPoseSelectingJob.h"

namespace throng::cascade {

const char* KeyPoseSelectingJob::problem() const {
    if (!caches || !decisions || !scratch) return "caches, decisions and scratch are required";
    const std::size_t n = decisions->outcome.size();
    if (decisions->cacheOf.size() != n || decisions->keyPoseOf.size() != n) return "cacheOf and keyPoseOf must have one entry per decision";
    return nullptr;
}

void KeyPoseSelectingJob::run(PhaseLoop& loop) const {
    throwIfInvalid("KeyPoseSelectingJob", loop.ready() ? problem() : "the loop has no frame");
    SurvivorDecisions& d = *decisions;
    Scratch& w = *scratch;
    const std::size_t n = d.outcome.size();
    ActorFrameStatistics& stats = loop.statistics();
    for (std::size_t ci = 0; ci < caches->size(); ++ci) {
        KeyPoseCache& cache = *(*caches)[ci];
        // Demands: in both modes an actor's second pose follows from its first (the same pose, or
        // the next key-pose of the clip), so counting first poses counts the demands.
        w.demandCount.assign(cache.poseCount(), 0);
        w.secondPose.assign(cache.poseCount(), KeyPoseRows::kNone);
        bool any = false;
        for (std::size_t k = 0; k < n; ++k) {
            if (d.outcome[k] != kCached || d.cacheOf[k] != ci) continue;
            const KeyPoseRef& ref = d.keyPoseOf[k];
            ++w.demandCount[ref.pose[0]];
            w.secondPose[ref.pose[0]] = ref.pose[1];
            any = true;
        }
        w.demand.clear();
        if (!any) {
            cache.recordDemand(w.demand);
            continue;
        }
        w.poseNeeded.assign(cache.poseCount(), 0);
        for (std::uint32_t p = 0; p < cache.poseCount(); ++p) {
            if (!w.demandCount[p]) continue;
            w.demand.push_back(KeyPoseDemand{p, w.secondPose[p], w.demandCount[p]});
            w.poseNeeded[p] = w.poseNeeded[w.secondPose[p]] = 1;
        }
        for (const std::uint8_t x : w.poseNeeded) stats.keyPosesWanted += x;
        cache.recordDemand(w.demand);
        KeyPoseRows& rows = cache.rows();
        rows.held(w.resident);
        selectKeyPosesGreedy(w.demand, rows.rowCount(), w.resident, w.selection, w.chosen);
        stats.keyPoseUpdates += rows.hold(w.chosen, frame);
        for (std::size_t k = 0; k < n; ++k) {
            if (d.outcome[k] != kCached || d.cacheOf[k] != ci) continue;
            KeyPoseRef& ref = d.keyPoseOf[k];
            ref.row[0] = rows.rowOf(ref.pose[0]);
            ref.row[1] = rows.rowOf(ref.pose[1]);
            if (ref.row[0] == KeyPoseRows::kNone || ref.row[1] == KeyPoseRows::kNone) {
                d.outcome[k] = kPosed;  // a pose did not fit: skinned as usual
                ++stats.keyPoseMisses;
                continue;
            }
            rows.touch(ref.pose[0], frame);
            rows.touch(ref.pose[1], frame);
            ++stats.keyPoseActors;
        }
        stats.keyPosesHeld += rows.heldCount();
    }
}

}  // namespace throng::cascade
