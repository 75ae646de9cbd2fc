#pragma once
// Phase 1, placed in the world: the generic matrices traversal hands each Actor or ActorGroup node
// to this job, which places its actors' Reference Points and Refpoint Bspheres under the node's
// parent and gives the node's bound.

#include <span>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/PhaseLoop.h"

namespace throng::cascade {

/// Places the Reference Points of the actors of one node in the world.
struct RefpointPlacementJob {
    /// In: refLocal and refSphereLocal of the actors.
    const Crowd::State* crowd = nullptr;
    /// In: the actors of the node.
    std::span<const ActorId> ids;
    /// In: the node's parent to world (ignored when parentIsIdentity).
    Mat4 parent{1.0};
    /// In: the parent is the identity (no matrix product per actor).
    bool parentIsIdentity = true;
    /// In: the node's declared roaming bound, or an invalid sphere: the bound is grown.
    BoundingSphere roaming;
    /// Out, per actor of the crowd: Reference Point in the world (only `ids` written).
    std::span<Mat4> refWorld;
    /// Out, per actor of the crowd: Refpoint Bsphere in the world (only `ids` written).
    std::span<BoundingSphere> refSphereWorld;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job and returns the node's bound: grown over the actors' spheres, or `roaming`
    /// widened only by a member outside it. Throws std::invalid_argument when it cannot run.
    BoundingSphere run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
