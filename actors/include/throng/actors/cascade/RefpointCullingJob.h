#pragma once
// Phase 2 of actor processing, CULL 1: Refpoint Bspheres against the frustum. A lone actor's and a
// group's sphere were tested by the generic CULL traversal; members of groups that cross a plane
// (stage kPending) are tested here, flat and several at a time, relative to the eye.

#include <span>
#include <vector>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/PhaseLoop.h"
#include "throng/scenegraph/Frustum.h"

namespace throng::cascade {

/// Decides every pending candidate by its Refpoint Bsphere and lists the survivors.
struct RefpointCullingJob {
    /// Flat arrays of the spheres under test, kept between frames.
    struct Scratch {
        std::vector<std::uint32_t> pending;  ///< candidate indices of the spheres in cx ... cr
        std::vector<float> cx;               ///< sphere centres relative to the eye: x
        std::vector<float> cy;               ///< y
        std::vector<float> cz;               ///< z
        std::vector<float> cr;               ///< sphere radii
        std::vector<Containment> containment;///< per pending sphere: the test's result
    };

    /// In: refSphereWorld of the candidates (every one present: see ActorProcessor).
    const Crowd::State* crowd = nullptr;
    /// In: the culling frustum.
    const Frustum* frustum = nullptr;
    /// In: the eye (spheres are tested relative to it, in single precision).
    Vec3 eye{0.0};
    /// In and out: the candidates; the pending ones get their stage and plane mask.
    std::span<Candidate> candidates;
    /// Out: candidate indices not outside, in candidate order.
    std::vector<std::uint32_t>* survivors = nullptr;
    /// Out, per actor of the crowd: ActorClass::A for the rejected. Counts a and spheresTested.
    std::span<ActorClass> actorClass;
    /// The job's workspace.
    Scratch* scratch = nullptr;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job; throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
