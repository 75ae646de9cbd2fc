#pragma once
// Phase 4 of actor processing, last step: the actors shown (in candidate order), room in the
// per-node arrays for the posed ones, and skeletal LOD: which Skeleton nodes each posed actor keeps.

#include <span>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/PhaseLoop.h"

namespace throng::cascade {

/// Lists the actors shown and the posed ones, and switches Skeleton nodes off by distance.
struct SkeletalLodJob {
    /// In: tmpl.
    const Crowd::State* crowd = nullptr;
    /// In: the candidates.
    std::span<const Candidate> candidates;
    /// In: candidate indices of the survivors.
    std::span<const std::uint32_t> survivors;
    /// In: CULL 2's decisions (outcome, detail2, level).
    const SurvivorDecisions* decisions = nullptr;
    /// In: deactivate Skeleton nodes by distance (false: every node stays active).
    bool skeletalLod = true;
    /// Out: shown, posedOf, posed, level, nodeBase, active; model and evaluated sized for phase 5.
    PosedActors* posed = nullptr;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job; throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
