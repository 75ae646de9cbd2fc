#pragma once
// Phase 5 of actor processing: each posed actor's behaviour writes the DOF values of its active
// Skeleton nodes at its behavioural level; their model matrices follow, several actors of one
// template at a time.

#include <span>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/PhaseLoop.h"

namespace throng::cascade {

/// Poses every posed actor: DOF values, then node-to-Skeleton-Root matrices.
struct BehavioursJob {
    /// In: tmpl, behaviour, slot, dofOffset.
    const Crowd::State* crowd = nullptr;
    /// In: the candidates.
    std::span<const Candidate> candidates;
    /// In: candidate indices of the survivors.
    std::span<const std::uint32_t> survivors;
    /// In: seconds of simulation time.
    double time = 0.0;
    /// In: posed, level, nodeBase, active. Out: model (per node) and evaluated (per posed).
    /// Counts actorsPosed and skeletonNodesEvaluated.
    PosedActors* posed = nullptr;
    /// Out: the DOF values of every actor (only the posed actors' active nodes written).
    std::span<float> dofs;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job; throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
