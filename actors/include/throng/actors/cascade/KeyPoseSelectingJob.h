#pragma once
// Phase 4 of actor processing, key-pose caches (Toledo et al.): from what the actors in each
// cache's band need this frame, the greedy selection chooses the poses the cache holds, the rows
// keep what they can from the last frame, and every actor whose poses are held is drawn from the
// cache (no behaviour, no matrices, no palette). The others are posed and skinned as usual.
// Serial, in candidate order: the same whatever the threads.

#include <cstdint>
#include <vector>

#include "throng/actors/KeyPoseArbiter.h"
#include "throng/actors/KeyPoseSelection.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/PhaseLoop.h"

namespace throng::cascade {

/// Chooses the poses each key-pose cache holds this frame, and which actors it shows.
struct KeyPoseSelectingJob {
    /// The selection's workspace, kept between frames.
    struct Scratch {
        std::vector<std::uint32_t> demandCount;  ///< per pose of the cache being counted: actors needing it first
        std::vector<std::uint32_t> secondPose;   ///< per pose: the second pose its actors need
        std::vector<std::vector<KeyPoseDemand>> demands;  ///< per cache: this process's demands
        KeyPoseSelector selector;                ///< the selection, when no arbiter makes it
    };

    /// In and out: the key-pose caches (demand recorded, rows updated).
    const std::vector<std::shared_ptr<KeyPoseCache>>* caches = nullptr;
    /// In: the frame number (the rows' least recently used order).
    std::uint64_t frame = 0;
    /// In and out: the kCached decisions; an actor whose poses did not fit becomes kPosed, the
    /// others get the rows. Counts keyPoseActors, keyPoseMisses, keyPoseUpdates, keyPosesWanted, keyPosesHeld.
    SurvivorDecisions* decisions = nullptr;
    /// The job's workspace.
    Scratch* scratch = nullptr;
    /// Null: this process selects for its own demands. Otherwise the arbiter settles the rows over
    /// the demands of every process showing some of the crowd; this process then reads them.
    KeyPoseArbiter* arbiter = nullptr;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job; throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
