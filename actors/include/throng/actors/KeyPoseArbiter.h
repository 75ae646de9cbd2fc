#pragma once
// Key-pose caches shared by processes that each show some actors of one crowd (ranks posing their
// own walkers, seed 004 with the crowd split): the poses a cache holds are chosen once, from every
// process's demands, as one process showing every actor would choose them; every process then
// draws its actors from the same rows. The selection depends on the demands only as counts per
// pair of poses, so the processes send those, not their actors.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "throng/actors/KeyPoseSelection.h"

namespace throng {

class KeyPoseCache;

/// What one frame's selection for a cache did (ActorFrameStatistics' keyPose counts).
struct KeyPoseSelectionCounts {
    std::uint64_t wanted = 0;   ///< distinct key-poses the demands need
    std::uint64_t updates = 0;  ///< key-poses newly stored in a row
    std::uint64_t held = 0;     ///< key-poses held in the rows after the update
};

/// Adds the demands of `part` to `combined` (both in increasing order of first pose, as
/// KeyPoseSelectingJob makes them, and kept so): the actors of equal demands are added.
void addKeyPoseDemands(std::vector<KeyPoseDemand>& combined, std::span<const KeyPoseDemand> part);

/// The selection of one frame: greedy choice of the poses a cache holds, the rows updated, and the
/// poses of every demand the rows then serve marked used. Keeps its scratch between frames.
class KeyPoseSelector {
public:
    /// Selects for `demand` (one process's, or every process's added) into `cache`'s rows in
    /// frame `frame` and records the demand in the cache. Nothing is selected for no demand.
    KeyPoseSelectionCounts select(KeyPoseCache& cache, std::span<const KeyPoseDemand> demand, std::uint64_t frame);

private:
    std::vector<std::uint8_t> poseNeeded_;
    std::vector<std::uint32_t> resident_, chosen_;
    KeyPoseSelectionWorkspace workspace_;
};

/// Settles the rows of the key-pose caches when several processes show one crowd. ActorProcessor
/// calls it once per frame in which its caches are on (setKeyPoseArbiter), in every process, at
/// the same point of every frame.
class KeyPoseArbiter {
public:
    virtual ~KeyPoseArbiter() = default;
    /// `demands`: this process's demands of each cache of `caches` (the processor's caches, in
    /// order) in frame `frame`. On return each cache's rows hold, in every process, what one
    /// selection over every process's demands chose (KeyPoseSelector on the added demands, then
    /// KeyPoseRows::copyRows elsewhere). Returns that selection's counts in the process that made
    /// it, zeros in the others (so that shares add up: addShare).
    virtual KeyPoseSelectionCounts settle(std::span<const std::vector<KeyPoseDemand>> demands,
                                          std::span<const std::shared_ptr<KeyPoseCache>> caches, std::uint64_t frame) = 0;
};

}  // namespace throng
