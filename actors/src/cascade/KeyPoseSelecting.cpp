// Phase 4 of actor processing, key-pose caches (see KeyPoseSelectingJob.h): Toledo et al.'s greedy
// selection (§4.2) over the demands of the frame.

#include "throng/actors/KeyPoseArbiter.h"
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
    // Demands: in both modes an actor's second pose follows from its first (the same pose, or the
    // next key-pose of the clip), so counting first poses counts the demands.
    w.demands.resize(caches->size());
    for (std::size_t ci = 0; ci < caches->size(); ++ci) {
        const KeyPoseCache& cache = *(*caches)[ci];
        w.demandCount.assign(cache.poseCount(), 0);
        w.secondPose.assign(cache.poseCount(), KeyPoseRows::kNone);
        for (std::size_t k = 0; k < n; ++k) {
            if (d.outcome[k] != kCached || d.cacheOf[k] != ci) continue;
            const KeyPoseRef& ref = d.keyPoseOf[k];
            ++w.demandCount[ref.pose[0]];
            w.secondPose[ref.pose[0]] = ref.pose[1];
        }
        std::vector<KeyPoseDemand>& demand = w.demands[ci];
        demand.clear();
        for (std::uint32_t p = 0; p < cache.poseCount(); ++p)
            if (w.demandCount[p]) demand.push_back(KeyPoseDemand{p, w.secondPose[p], w.demandCount[p]});
    }
    // The rows: selected here for this process's demands, or settled over every process's.
    KeyPoseSelectionCounts counts;
    if (arbiter) {
        counts = arbiter->settle(w.demands, *caches, frame);
    } else {
        for (std::size_t ci = 0; ci < caches->size(); ++ci) {
            const KeyPoseSelectionCounts c = w.selector.select(*(*caches)[ci], w.demands[ci], frame);
            counts.wanted += c.wanted, counts.updates += c.updates, counts.held += c.held;
        }
    }
    stats.keyPosesWanted += counts.wanted;
    stats.keyPoseUpdates += counts.updates;
    stats.keyPosesHeld += counts.held;
    // Every actor whose poses are held is drawn from them; the others are skinned as usual.
    for (std::size_t k = 0; k < n; ++k) {
        if (d.outcome[k] != kCached) continue;
        const KeyPoseRows& rows = (*caches)[d.cacheOf[k]]->rows();
        KeyPoseRef& ref = d.keyPoseOf[k];
        ref.row[0] = rows.rowOf(ref.pose[0]);
        ref.row[1] = rows.rowOf(ref.pose[1]);
        if (ref.row[0] == KeyPoseRows::kNone || ref.row[1] == KeyPoseRows::kNone) {
            d.outcome[k] = kPosed;  // a pose did not fit: skinned as usual
            ++stats.keyPoseMisses;
        } else {
            ++stats.keyPoseActors;
        }
    }
}

}  // namespace throng::cascade
