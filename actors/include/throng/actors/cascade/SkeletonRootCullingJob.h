#pragma once
// Phase 4 of actor processing, CULL 2: the Sklsroot Bsphere of every survivor whose Refpoint
// Bsphere crosses a plane, then the survivors' Sklsroot Bspheres against the occlusion buffer
// (when there is one); one eye distance per actor that passes (every later LOD decision reads it);
// the hybrid tier (impostor or geometry, with hysteresis); the behavioural level; the key-pose band.

#include <span>
#include <vector>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/PhaseLoop.h"

namespace throng {
class OcclusionBuffer;
}

namespace throng::cascade {

/// Decides, for every survivor of CULL 1, whether it is rejected, posed, an impostor or cached.
struct SkeletonRootCullingJob {
    /// In: tmpl, behaviour, slot, sklsWorld, sklsRadius, refSphereWorld, priority, held.
    const Crowd::State* crowd = nullptr;
    /// In: the culling frustum.
    const Frustum* frustum = nullptr;
    /// In: the eye.
    Vec3 eye{0.0};
    /// In: seconds of simulation time (the clip time of cached actors).
    double time = 0.0;
    /// In: the frame's LOD, impostor and key-pose settings.
    const Settings* settings = nullptr;
    /// In: this frame's occluders, or null.
    const OcclusionBuffer* occlusion = nullptr;
    /// In and out: the candidates (stage after CULL 1); plane masks narrowed by the Sklsroot Bsphere.
    std::span<Candidate> candidates;
    /// In: candidate indices of the survivors.
    std::span<const std::uint32_t> survivors;
    /// In and out, per actor, kept across frames: 1 while an impostor (grown to the crowd's size).
    std::vector<std::uint8_t>* impostorTier = nullptr;
    /// In and out, per actor, kept across frames: 1 while in the key-pose band (idem).
    std::vector<std::uint8_t>* keyPoseTier = nullptr;
    /// Out, per actor of the crowd: B, C1, C2, C3_1 (refined by CULL 3) or Occluded. Counts b, c1,
    /// c2, occludedSklsroot, occlusionTests, spheresTested, lodDistances, eyeDistances, impostors, keyPoseBand.
    std::span<ActorClass> actorClass;
    /// Out, per actor of the crowd: the eye distance of every actor not rejected.
    std::span<double> eyeDistance;
    /// Out: one decision per survivor.
    SurvivorDecisions* decisions = nullptr;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job; throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
