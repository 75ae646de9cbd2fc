// Phase 4 of actor processing, key-pose caches (seed 004): from what the actors in each cache's
// band need this frame, the greedy selection of §4.2 chooses the poses the cache holds, the rows
// keep what they can from the last frame, and every actor whose poses are held is drawn from the
// cache (no behaviour, no matrices, no palette: its pose was evaluated once, for the cache). The
// others are posed and skinned as usual. Serial, in candidate order: the same whatever the threads.

#include "CascadeFrame.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/actors/KeyPoseSelection.h"

namespace throng::cascade {

void selectKeyPoses(CascadeFrame& f) {
    const auto& caches = *f.settings.keyPoseCaches;
    const std::size_t n = f.survivors.size();
    ActorFrameStatistics& stats = *f.stats;
    std::vector<KeyPoseDemand>& demand = f.demand;
    for (std::size_t ci = 0; ci < caches.size(); ++ci) {
        KeyPoseCache& cache = *caches[ci];
        // Demands: in both modes an actor's second pose follows from its first (the same pose, or
        // the next key-pose of the clip), so counting first poses counts the demands.
        f.demandCount.assign(cache.poseCount(), 0);
        std::vector<std::uint32_t>& second = f.secondPose;
        second.assign(cache.poseCount(), KeyPoseRows::kNone);
        bool any = false;
        for (std::size_t k = 0; k < n; ++k) {
            if (f.outcome[k] != kCached || f.cacheOf[k] != ci) continue;
            const KeyPoseRef& ref = f.keyPoseOf[k];
            ++f.demandCount[ref.pose[0]];
            second[ref.pose[0]] = ref.pose[1];
            any = true;
        }
        demand.clear();
        if (!any) {
            cache.recordDemand(demand);
            continue;
        }
        std::vector<std::uint8_t>& needed = f.poseNeeded;
        needed.assign(cache.poseCount(), 0);
        for (std::uint32_t p = 0; p < cache.poseCount(); ++p) {
            if (!f.demandCount[p]) continue;
            demand.push_back(KeyPoseDemand{p, second[p], f.demandCount[p]});
            needed[p] = needed[second[p]] = 1;
        }
        for (const std::uint8_t x : needed) stats.keyPosesWanted += x;
        cache.recordDemand(demand);
        KeyPoseRows& rows = cache.rows();
        rows.held(f.resident);
        selectKeyPosesGreedy(demand, rows.rowCount(), f.resident, f.selection, f.chosen);
        stats.keyPoseUpdates += rows.hold(f.chosen, f.context.frame);
        for (std::size_t k = 0; k < n; ++k) {
            if (f.outcome[k] != kCached || f.cacheOf[k] != ci) continue;
            KeyPoseRef& ref = f.keyPoseOf[k];
            ref.row[0] = rows.rowOf(ref.pose[0]);
            ref.row[1] = rows.rowOf(ref.pose[1]);
            if (ref.row[0] == KeyPoseRows::kNone || ref.row[1] == KeyPoseRows::kNone) {
                f.outcome[k] = kPosed;  // a pose did not fit: skinned as usual
                ++stats.keyPoseMisses;
                continue;
            }
            rows.touch(ref.pose[0], f.context.frame);
            rows.touch(ref.pose[1], f.context.frame);
            ++stats.keyPoseActors;
        }
        stats.keyPosesHeld += rows.heldCount();
    }
}

}  // namespace throng::cascade
