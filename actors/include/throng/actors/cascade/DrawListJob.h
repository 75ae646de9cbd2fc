#pragma once
// Phase 7 of actor processing: the draw list. Impostors are placed at their Reference Point; actors
// drawn from a key-pose cache by their Skeleton Root; posed actors give their actor-level geometry
// (skinned with its palette, computed straight into the list) and each visible active node's
// geometry at its vaLod level, and their held objects. Each chunk writes its own segment of the list.

#include <span>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/PhaseLoop.h"

namespace throng::cascade {

/// Writes the draw items of every actor shown.
struct DrawListJob {
    /// In: tmpl, behaviour, slot, tint, refWorld, sklsWorld, held, heldObjects.
    const Crowd::State* crowd = nullptr;
    /// In: the culling frustum (held objects of actors decided part by part are tested).
    const Frustum* frustum = nullptr;
    /// In: seconds of simulation time (each item's clip time).
    double time = 0.0;
    /// In: the impostor of each template.
    const Settings* settings = nullptr;
    /// In: the candidates.
    std::span<const Candidate> candidates;
    /// In: candidate indices of the survivors.
    std::span<const std::uint32_t> survivors;
    /// In: CULL 2's decisions (outcome, detail2, keyPoseOf).
    const SurvivorDecisions* decisions = nullptr;
    /// In: the actors shown and the posed ones.
    const PosedActors* posed = nullptr;
    /// In: what CULL 3 left visible.
    const InternalVisibility* visibility = nullptr;

    /// Null when the job can run (the loop must draw into a list), else what is wrong.
    const char* problem(const PhaseLoop& loop) const;
    /// True when the job can run on `loop`.
    bool validate(const PhaseLoop& loop) const { return problem(loop) == nullptr; }
    /// Runs the job, the items going to the loop's draw list (counts drawItems and primitives);
    /// throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
