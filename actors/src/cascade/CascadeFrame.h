#pragma once
// Internal to actors: one frame of actor processing (seed 002 §4.2) — what the frame is (crowd,
// frustum, eye, time, settings) and the workspace its seven phases share. The workspace is kept
// by the ActorProcessor and reused from frame to frame, so a warm frame allocates nothing.
// Per-actor phases run in fixed chunks (forEachChunk); whatever a chunk produces (counts, FMULT
// tallies, draw items) goes to its ChunkOutput and is joined in chunk order, so the frame's
// results do not depend on the number of threads.

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>

#include "throng/actors/ActorFrameStatistics.h"
#include "throng/actors/ActorId.h"
#include "throng/actors/Affine.h"
#include "throng/actors/KeyPoseSelection.h"
#include "throng/actors/detail/PoseBatch.h"
#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/FrameContext.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/scenegraph/ThreadTeam.h"

namespace throng {

class ActorTemplate;
class Crowd;
class KeyPoseCache;
class Drawable;
class Node;
class OcclusionBuffer;

namespace cascade {

/// Elements per chunk of the light per-actor loops (Reference Points, Skeleton Roots, CULL 1 and 2).
inline constexpr std::size_t kLightGrain = 512;
/// Elements per chunk of the heavy ones (poses, CULL 3, draw items).
inline constexpr std::size_t kHeavyGrain = 64;

/// Where a candidate stands after CULL 1.
enum Stage : std::uint8_t {
    kPending = 0,   ///< a group member whose Refpoint Bsphere is still to be tested
    kInside = 1,    ///< Refpoint Bsphere inside every plane
    kCrossing = 2,  ///< Refpoint Bsphere crosses a plane
    kOutside = 3,   ///< rejected by CULL 1
};

/// What CULL 2 decided for a survivor of CULL 1.
enum Outcome : std::uint8_t {
    kRejected = 0,  ///< Sklsroot Bsphere outside (C1)
    kPosed = 1,     ///< goes on to phases 5-7 with its geometry
    kImpostor = 2,  ///< drawn as an impostor; no Skeleton node processed
    kCached = 3,    ///< in a key-pose cache's band: drawn from the cache if its poses are held
};

/// Which parts of a posed actor CULL 3 left visible.
enum Visibility : std::uint8_t {
    kNoneVisible = 0,  ///< none: the whole internal bound was outside
    kAllVisible = 1,   ///< all: the Sklsroot Bsphere or the whole internal bound was inside
    kPerPart = 2,      ///< decided part by part (C3.2)
};

/// Plane mask of a node whose subtree sphere was found outside.
inline constexpr PlaneMask kCulled = 0xFF;

/// One actor reaching CULL 1, and what the cascade found.
struct Candidate {
    ActorId id;              ///< the actor
    const Node* node;        ///< the node holding it
    std::uint32_t member;    ///< its index in that node
    PlaneMask mask;          ///< planes still crossed after the last test
    std::uint8_t stage;      ///< a Stage
};

/// What the processor's settings say for this frame.
struct Settings {
    double lodScale2 = 1.0;                 ///< LOD scale squared
    bool skeletalLod = true;                ///< deactivate Skeleton nodes by distance
    bool behaviouralLod = true;             ///< behaviours run at their distance level
    double impostorDistance = 0.0;          ///< 0: no impostors
    double impostorHysteresis = 0.0;        ///< metres either side of the distance
    /// Impostor drawable of each template that has one.
    const std::vector<std::pair<const ActorTemplate*, std::shared_ptr<const Drawable>>>* impostors = nullptr;
    double keyPoseDistance = 0.0;           ///< start of the key-pose band (0: no caches)
    double keyPoseHysteresis = 0.0;         ///< metres either side of it
    /// Key-pose cache of each template that has one.
    const std::vector<std::shared_ptr<KeyPoseCache>>* keyPoseCaches = nullptr;
};

/// What one chunk of a parallel phase produced.
struct ChunkOutput {
    ActorFrameStatistics counts;      ///< counters only (no times)
    OpCounter ops;                    ///< FMULT tallies, enabled when the frame counts
    DrawSegment* items = nullptr;     ///< where its draw items go (phase 7): its own segment of the frame's list
    BoundingSphere bound;             ///< a group's bound, merged from its chunk's Refpoint Bspheres
    detail::PoseBatchWorkspace pose;  ///< scratch of the pose batches (phase 5)
};

/// One frame of actor processing and the workspace of its phases.
struct CascadeFrame {
    // The frame.
    Crowd* crowd = nullptr;                 ///< the actors
    Frustum frustum;                        ///< the culling frustum
    Vec3 eye{0.0};                          ///< the eye
    FrameContext context;                   ///< time, frame number, counter (null when not counting)
    Settings settings;                      ///< LOD and impostor settings
    ActorFrameStatistics* stats = nullptr;  ///< where the frame's statistics go
    DrawList* drawList = nullptr;           ///< where the frame's draw items go
    const OcclusionBuffer* occlusion = nullptr;  ///< this frame's occluders, or null: no occlusion

    // Phase 2: candidates, and the flat arrays of the Refpoint Bspheres still to test.
    std::vector<Candidate> candidates;
    std::vector<std::uint32_t> pending;     ///< candidate indices of the spheres in cx ... cr
    std::vector<float> cx, cy, cz, cr;
    std::vector<Containment> containment;
    std::vector<std::uint32_t> survivors;   ///< candidate indices that passed CULL 1

    // Phase 2, occlusion: survivors binned into cells of nearby actors, each cell tested first.
    std::vector<std::uint32_t> cellOf;      ///< per survivor: its cell
    std::vector<std::uint32_t> cellStart;   ///< per cell: first entry in cellMembers (one more at the end)
    std::vector<std::uint32_t> cellMembers; ///< survivor positions, cell by cell
    std::vector<std::uint32_t> cellCursor;  ///< per cell: where its next member goes
    std::vector<std::uint8_t> hidden;       ///< per survivor: rejected by occlusion

    // Phase 4, per survivor.
    std::vector<std::uint8_t> outcome;      ///< an Outcome
    std::vector<double> detail2;            ///< squared detail distance

    // Phases 5-7: actors shown (posed or impostors) in candidate order, and the posed ones.
    std::vector<std::uint32_t> shown;       ///< survivor indices not rejected by CULL 2
    std::vector<std::uint32_t> posedOf;     ///< per shown actor: its index among the posed, or kNotPosed
    std::vector<std::uint32_t> posed;       ///< survivor indices of posed actors
    std::vector<int> level;                 ///< per posed: behavioural level
    std::vector<std::uint32_t> nodeBase;    ///< per posed: first entry in the per-node arrays
    std::vector<std::uint32_t> evaluated;   ///< per posed: Skeleton nodes evaluated
    std::vector<std::uint8_t> visibility;   ///< per posed: a Visibility
    std::vector<std::uint8_t> rootVisible;  ///< per posed: its actor-level geometry is visible
    std::vector<std::uint8_t> active;       ///< per node of each posed actor
    std::vector<std::uint8_t> visible;      ///< per node of each posed actor, after CULL 3
    std::vector<Affine> model;              ///< per node: node to Skeleton Root
    std::vector<BoundingSphere> geometry, subtree;  ///< per node: internal spheres, Skeleton Root frame
    std::vector<PlaneMask> masks;           ///< per node: planes still crossed
    std::vector<std::uint8_t>* impostorTier = nullptr;  ///< per actor, kept across frames: 1 while an impostor
    std::vector<std::uint8_t>* keyPoseTier = nullptr;   ///< per actor, kept across frames: 1 while in the key-pose band

    // Phase 4, key-pose caches: per survivor in the band, its cache and the poses it needs; per
    // posed-or-cached shown actor, what phase 7 draws from the cache.
    std::vector<std::uint16_t> cacheOf;     ///< per survivor: index in settings.keyPoseCaches (kCached only)
    std::vector<KeyPoseRef> keyPoseOf;      ///< per survivor: poses needed, then the rows holding them
    std::vector<std::uint32_t> demandCount; ///< per pose of the cache being selected: actors needing it (as first pose)
    std::vector<std::uint32_t> secondPose;  ///< per pose of the cache being selected: the second pose its actors need
    std::vector<std::uint8_t> poseNeeded;   ///< per pose of the cache being selected: some actor needs it
    std::vector<KeyPoseDemand> demand;      ///< the demands of the cache being selected
    std::vector<std::uint32_t> resident;    ///< the poses its rows held before the selection
    std::vector<std::uint32_t> chosen;      ///< the poses selected
    KeyPoseSelectionWorkspace selection;    ///< the selection's scratch

    std::vector<ChunkOutput> chunks;        ///< one per chunk of the current parallel loop

    /// Marks a shown actor that is not posed.
    static constexpr std::uint32_t kNotPosed = ~std::uint32_t{0};

    /// Runs body(out, begin, end) over [0, n) in fixed chunks of `grain`, each with its own
    /// output (counts zeroed, FMULT counter enabled when the frame counts), then adds every
    /// chunk's counts and tallies to the frame's, in chunk order.
    template <class Body>
    void parallel(std::size_t n, std::size_t grain, Body&& body) {
        inChunks(n, grain, false, body);
    }
    /// parallel(), each chunk writing its draw items into a segment of the frame's list of its
    /// own, opened in chunk order: the items are written once, where DRAW reads them.
    template <class Body>
    void parallelDrawing(std::size_t n, std::size_t grain, Body&& body) {
        inChunks(n, grain, true, body);
    }
    /// What parallel() and parallelDrawing() do.
    template <class Body>
    void inChunks(std::size_t n, std::size_t grain, bool drawing, Body& body) {
        const std::size_t count = chunkCount(n, grain);
        prepareChunks(count);
        if (drawing) {
            const std::size_t first = drawList->openSegments(count);
            for (std::size_t c = 0; c < count; ++c) chunks[c].items = &drawList->segment(first + c);
        }
        forEachChunk(n, grain, [&](std::size_t c, std::size_t begin, std::size_t end) { body(chunks[c], begin, end); });
        joinChunks(count);
    }
    /// Gets `count` chunk outputs ready (reused, grown when needed).
    void prepareChunks(std::size_t count);
    /// Adds the counts and tallies of the first `count` chunks to the frame's.
    void joinChunks(std::size_t count);
    /// The counter a chunk's work goes to, or null when not counting.
    OpCounter* counterOf(ChunkOutput& out) const { return context.counter ? &out.ops : nullptr; }
};

/// Adds the counters (not the times) of `from` to `into`.
void addCounts(ActorFrameStatistics& into, const ActorFrameStatistics& from);

// The seven phases, in order. Each works on the frame's workspace only.

/// Phase 1: the Reference Point of every actor, in the scene or not, whatever the camera.
void computeReferencePoints(CascadeFrame& f);
/// Phase 1, placed in the world by the generic matrices traversal: Reference Points and Refpoint
/// Bspheres of the actors `ids` under `parent`; returns the bound of them all: grown over them, or
/// `roaming` (when valid) widened only by a member outside it.
BoundingSphere placeReferencePoints(CascadeFrame& f, std::span<const ActorId> ids, const Mat4& parent, bool parentIsIdentity,
                                   const BoundingSphere& roaming);
/// Phase 2: CULL 1 on the Refpoint Bspheres of group members still pending (flat, several at a
/// time), then the survivors.
void cullReferencePoints(CascadeFrame& f);
/// Phase 2, occlusion (when the frame has a buffer): the survivors' Refpoint Bspheres against it,
/// cells of nearby actors tested as one sphere first; hidden actors leave the survivors.
void occludeReferencePoints(CascadeFrame& f);
/// Phase 3: the Skeleton Roots of the survivors.
void computeSkeletonRoots(CascadeFrame& f);
/// Phase 4: CULL 2 on Sklsroot Bspheres, then occlusion; one eye distance per actor; impostor
/// tier; skeletal LOD.
void cullSkeletonRoots(CascadeFrame& f);
/// Phase 4, key-pose caches: chooses the poses each cache holds from what the actors in its band
/// need (greedy, seed 004 §4.2), updates the rows; actors whose poses are held stay kCached, the
/// others are posed as usual. Serial and in candidate order: deterministic whatever the threads.
void selectKeyPoses(CascadeFrame& f);
/// Phase 5: behaviour of the active Skeleton nodes at each posed actor's level, and their matrices.
void evaluateBehaviours(CascadeFrame& f);
/// Phase 6: CULL 3 on internal spheres, only for actors whose Sklsroot Bsphere crosses a plane.
void cullInternalSpheres(CascadeFrame& f);
/// Phase 7: the draw list: each visible part at its vaLod level, impostors at their Reference Point.
void buildDrawList(CascadeFrame& f);

}  // namespace cascade
}  // namespace throng
