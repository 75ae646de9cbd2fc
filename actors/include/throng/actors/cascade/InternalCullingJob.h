#pragma once
// Phase 6 of actor processing, CULL 3: hierarchical internal bounding spheres, only for actors whose
// Sklsroot Bsphere crosses a plane (class C3). The whole internal bound decides first (C3.1: wholly
// in or out); otherwise (C3.2) the actor-level geometry and each active node are tested depth first
// with plane masks, as traditional CULL tests them.

#include <span>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/PhaseLoop.h"

namespace throng::cascade {

/// Decides which parts of each posed actor crossing the frustum are visible.
struct InternalCullingJob {
    /// In: tmpl, sklsWorld, held, heldObjects.
    const Crowd::State* crowd = nullptr;
    /// In: the culling frustum.
    const Frustum* frustum = nullptr;
    /// In: the candidates (plane masks after CULL 1).
    std::span<const Candidate> candidates;
    /// In: candidate indices of the survivors.
    std::span<const std::uint32_t> survivors;
    /// In: CULL 2's decisions (detail2).
    const SurvivorDecisions* decisions = nullptr;
    /// In: the posed actors, their active nodes and model matrices.
    const PosedActors* posed = nullptr;
    /// In and out, per actor of the crowd: C3_1 becomes C3_2 when decided part by part. Counts
    /// c3_1, c3_2, internalSpheresComputed, spheresTested.
    std::span<ActorClass> actorClass;
    /// Out: what is visible.
    InternalVisibility* visibility = nullptr;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job; throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
