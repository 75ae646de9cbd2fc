#pragma once
// Per-frame statistics of actor or traditional processing: time per phase, where actors left the
// culling cascade (seed 002 Table 2), and the work done on Skeleton nodes and internal spheres.
// The simulation step is not part of them: the frame loop steps the crowd before APP and CULL
// (Crowd::step) and times it apart.

#include <cstdint>

#include "throng/scenegraph/FrameStatistics.h"

namespace throng {

/// How a scene is processed.
enum class Processing : std::uint8_t {
    Traditional,  ///< as a generic scenegraph: every behaviour, matrix and sphere, then CULL
    Actor,        ///< the seven phases of seed 002 §4.2
};

/// What one frame cost and produced. Every actor in the scene is counted in exactly one of
/// culledWithGroup, a, b, c1, c2, c3_1, c3_2 and the three occluded counts.
struct ActorFrameStatistics {
    Processing processing = Processing::Actor;  ///< method used
    std::uint64_t frame = 0;                    ///< frame number

    // Time per phase, milliseconds. Traditional processing fills app, matricesBounds and cull.
    double appMs = 0;             ///< generic APP (traditional: every actor's behaviour too)
    double refpointMs = 0;        ///< phase 1: Reference Points of all actors
    double matricesBoundsMs = 0;  ///< generic matrices and bounds (traditional: all actor matrices and spheres)
    double cullMs = 0;            ///< generic CULL and CULL 1 (phase 2); traditional: the whole CULL
    double occlusionBufferMs = 0; ///< occlusion: gathering and drawing the occluders, the pyramid
    double refpointOcclusionMs = 0;///< occlusion of the Refpoint Bspheres that passed CULL 1
    double skeletonRootMs = 0;    ///< phase 3: Skeleton Roots of the survivors
    double cull2Ms = 0;           ///< phase 4: CULL 2, eye distances, skeletal LOD (key-pose selection included)
    double keyPoseSelectMs = 0;   ///< of cull2Ms: choosing the key-poses the caches hold
    double poseMs = 0;            ///< phase 5: behaviour of active nodes and their matrices
    double cull3Ms = 0;           ///< phase 6: CULL 3 on internal spheres
    double drawListMs = 0;        ///< phase 7: the draw list
    double drawMs = 0;            ///< DRAW, when the processor was given a backend

    // The cascade (actor processing), as in Table 2.
    std::uint64_t actorsInScene = 0;    ///< actors held by a node of the scene
    /// Of the actors in the scene, those another process simulates or shows (Behaviour::presence):
    /// rejected unread, and counted in `a`.
    std::uint64_t actorsAbsent = 0;
    std::uint64_t culledWithGroup = 0;  ///< rejected with a generic group above them
    std::uint64_t a = 0;                ///< A: Refpoint Bsphere outside (rejected by CULL 1)
    std::uint64_t b = 0;                ///< B: Refpoint Bsphere inside
    std::uint64_t c1 = 0;               ///< C1: Sklsroot Bsphere outside (rejected by CULL 2)
    std::uint64_t c2 = 0;               ///< C2: Sklsroot Bsphere inside
    std::uint64_t c3_1 = 0;             ///< C3.1: internal spheres wholly in or out
    std::uint64_t c3_2 = 0;             ///< C3.2: internal spheres culled one by one

    // Occlusion (zero when it is off): actors rejected at each stage, and the stage's work.
    std::uint64_t occludedWithGroup = 0;   ///< with their actor group's sphere, during the traversal
    std::uint64_t occludedRefpoint = 0;    ///< by their Refpoint Bsphere, after CULL 1
    std::uint64_t occludedSklsroot = 0;    ///< by their Sklsroot Bsphere, after CULL 2
    std::uint64_t occlusionCellsTested = 0;///< cells of nearby actors tested as one sphere after CULL 1
    std::uint64_t occlusionCellsHidden = 0;///< of those, hidden (their actors rejected with one test)
    /// Sphere tests against the buffer, all kinds. Cells never span two regions of the actors'
    /// behaviour, and a process testing against another's buffer (setSharedOcclusionBuffer) counts
    /// no node, that one does: split over processes by region, the sums are one process's.
    std::uint64_t occlusionTests = 0;
    /// Objects tested against the buffer: generic nodes, the actors rejected with their group's
    /// sphere, actors after CULL 1 (alone or with their cell) and after CULL 2, once per stage (a
    /// process testing against another's buffer counts no node). However the actors are split over
    /// processes, the sum is one process's: occlusion's rest weighs the rejections against it.
    std::uint64_t occlusionObjectsTested = 0;
    std::uint64_t nodesOccluded = 0;       ///< generic nodes rejected by occlusion (town tiles...); see occlusionTests
    std::uint64_t occludersDrawn = 0;      ///< Occluder nodes drawn into the buffer
    bool occlusionRested = false;          ///< occlusion rested this frame (OcclusionSettings::restFrames)

    // Work.
    std::uint64_t actorsPosed = 0;            ///< actors whose behaviour posed them this frame
    std::uint64_t impostors = 0;              ///< actors drawn as impostors (no Skeleton node processed)

    // Key-pose caches (seed 004; zero when none is set).
    std::uint64_t keyPoseBand = 0;            ///< actors in the caches' band this frame
    std::uint64_t keyPoseActors = 0;          ///< of those, drawn from a cache (no Skeleton node processed)
    std::uint64_t keyPoseMisses = 0;          ///< of those, posed and skinned as usual: a pose did not fit
    std::uint64_t keyPoseUpdates = 0;         ///< key-poses newly stored in a row (each skinned once in DRAW)
    std::uint64_t keyPosesWanted = 0;         ///< distinct key-poses the band's actors needed
    std::uint64_t keyPosesHeld = 0;           ///< key-poses held in the rows after the update
    std::uint64_t skeletonNodesEvaluated = 0; ///< Skeleton nodes whose DOFs and matrix were computed
    std::uint64_t internalSpheresComputed = 0;///< internal spheres recomputed
    std::uint64_t spheresTested = 0;          ///< sphere-frustum tests, all kinds
    std::uint64_t lodDistances = 0;           ///< eye distances computed for LOD (NO_05)
    /// Eye distances computed for actors: actor processing computes exactly one per actor that
    /// passes CULL 2 (every LOD decision of that actor reads it); traditional processing none here
    /// (each of its LOD nodes computes its own, counted in lodDistances).
    std::uint64_t eyeDistances = 0;
    std::uint64_t drawItems = 0;              ///< items in the draw list
    std::uint64_t primitives = 0;             ///< their primitives
    std::uint64_t fmultTotal = 0;             ///< FMULT counted (0 when counting is off)

    /// Everything before DRAW.
    double appCullMs() const {
        return appMs + refpointMs + matricesBoundsMs + occlusionBufferMs + cullMs + refpointOcclusionMs + skeletonRootMs + cull2Ms + poseMs + cull3Ms + drawListMs;
    }
};

/// Adds to `whole` the counts of `share`: one frame of a process that showed some of the scene's
/// actors, the others absent there (Behaviour::presence). Processes that between them show each
/// actor once add up to the counts of one process showing every actor: the actors in the scene
/// are counted once, an absent actor only where no process showed it, the other classes and the
/// per-actor work are summed. Times, the occluders drawn and the key-pose caches' rows are left as
/// they are (the processes ran side by side; the buffer and the caches are one process's). Exact when a group's bound
/// does not depend on which members are present (a roaming bound); otherwise a process may cull a
/// group whole where one process would test its members, and the classes (not the items) differ.
inline void addShare(ActorFrameStatistics& whole, const ActorFrameStatistics& share) {
    if (whole.actorsInScene == 0) whole.actorsInScene = whole.actorsAbsent = whole.a = share.actorsInScene;  // none shown yet
    const std::uint64_t shown = (whole.actorsInScene - whole.actorsAbsent) + (share.actorsInScene - share.actorsAbsent);
    const std::uint64_t shownA = (whole.a - whole.actorsAbsent) + (share.a - share.actorsAbsent);
    whole.actorsAbsent = shown < whole.actorsInScene ? whole.actorsInScene - shown : 0;
    whole.a = shownA + whole.actorsAbsent;
    const auto sum = [&](std::uint64_t ActorFrameStatistics::*count) { whole.*count += share.*count; };
    for (auto count : {&ActorFrameStatistics::culledWithGroup, &ActorFrameStatistics::b, &ActorFrameStatistics::c1,
                       &ActorFrameStatistics::c2, &ActorFrameStatistics::c3_1, &ActorFrameStatistics::c3_2,
                       &ActorFrameStatistics::occludedWithGroup, &ActorFrameStatistics::occludedRefpoint,
                       &ActorFrameStatistics::occludedSklsroot, &ActorFrameStatistics::occlusionCellsTested,
                       &ActorFrameStatistics::occlusionCellsHidden, &ActorFrameStatistics::occlusionTests,
                       &ActorFrameStatistics::occlusionObjectsTested,
                       &ActorFrameStatistics::actorsPosed, &ActorFrameStatistics::impostors, &ActorFrameStatistics::keyPoseBand,
                       &ActorFrameStatistics::keyPoseActors, &ActorFrameStatistics::keyPoseMisses,
                       &ActorFrameStatistics::skeletonNodesEvaluated, &ActorFrameStatistics::internalSpheresComputed,
                       &ActorFrameStatistics::spheresTested, &ActorFrameStatistics::lodDistances, &ActorFrameStatistics::eyeDistances,
                       &ActorFrameStatistics::drawItems, &ActorFrameStatistics::primitives, &ActorFrameStatistics::fmultTotal})
        sum(count);
}

}  // namespace throng
