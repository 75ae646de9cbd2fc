#pragma once
// Phase 3 of actor processing: the Skeleton Roots of the actors that passed CULL 1, each at the
// behavioural level its Reference Point's distance gives (the Skeleton Root is not placed yet).

#include <span>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/PhaseLoop.h"

namespace throng::cascade {

/// Computes the Skeleton Root of every survivor, relative to its Reference Point and in the world.
struct SkeletonRootsJob {
    /// In: behaviour, slot, refWorld, refSphereWorld, priority.
    const Crowd::State* crowd = nullptr;
    /// In: the candidates.
    std::span<const Candidate> candidates;
    /// In: candidate indices of the survivors of CULL 1.
    std::span<const std::uint32_t> survivors;
    /// In: the eye (the behavioural level goes by the Reference Point's distance).
    Vec3 eye{0.0};
    /// In: seconds of simulation time.
    double time = 0.0;
    /// In: behaviours run at their distance level.
    bool behaviouralLod = true;
    /// In: LOD scale squared.
    double lodScale2 = 1.0;
    /// Out, per actor of the crowd: the Skeleton Root relative to the Reference Point.
    std::span<RootPose> root;
    /// Out, per actor of the crowd: the Skeleton Root in the world.
    std::span<Mat4> sklsWorld;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job; throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
