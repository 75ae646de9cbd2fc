#pragma once
// Processes a scene holding actors one frame at a time, by traditional processing or by actor
// processing (seed 002 §4.2), on the very same scene:
//   1. Reference Points of all actors (simulation state, whatever the camera);
//   2. CULL 1: Refpoint Bspheres (after generic groups above them) - rejects A;
//   3. Skeleton Roots of the survivors;
//   4. CULL 2: Sklsroot Bspheres - rejects C1; one eye distance per actor; skeletal LOD;
//   5. behaviour of the active Skeleton nodes at the actor's behavioural level, and their matrices;
//   6. CULL 3: internal spheres, only for actors whose Sklsroot Bsphere crosses a plane;
//   7. the draw list, each part at its vaLod level.
// Generic nodes of the scene are processed as TraditionalProcessor does in both methods.

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "throng/actors/ActorFrameStatistics.h"
#include "throng/actors/ActorId.h"
#include "throng/actors/ActorTraversal.h"
#include "throng/actors/Affine.h"
#include "throng/actors/WorkerPool.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/TraditionalProcessor.h"

namespace throng {

class Camera;
class Crowd;
class DrawBackend;
class Node;

/// Frame processor for scenes with actors of one Crowd.
class ActorProcessor : private ActorTraversal {
public:
    /// Processes scenes whose actors live in `crowd` (which must outlive the processor).
    explicit ActorProcessor(Crowd& crowd);

    /// Chooses the method (default: actor processing).
    void setProcessing(Processing processing) { processing_ = processing; }
    /// The method in use.
    Processing processing() const { return processing_; }
    /// LOD scale (distance multiplier, > 0; above 1 lowers detail sooner).
    void setLodScale(double scale);
    /// Switches skeletal LOD (actor processing): off, every Skeleton node is processed.
    void setSkeletalLod(bool on) { skeletalLod_ = on; }
    /// Switches behavioural LOD (actor processing): off, behaviours always run at level 0.
    void setBehaviouralLod(bool on) { behaviouralLod_ = on; }
    /// Culls against `frustum` instead of the camera's (null restores the camera's).
    void setCullingFrustum(std::optional<Frustum> frustum);
    /// Runs the per-actor phases (Reference Points, Skeleton Roots, poses) on `threads` threads
    /// (default 1). Results are bitwise identical whatever the number; with FMULT counting on,
    /// everything runs on the calling thread.
    void setThreads(unsigned threads);
    /// Operation counter (disabled until counter().setEnabled(true)); shared by both methods.
    OpCounter& counter() { return traditional_.counter(); }

    /// Processes one frame at `time` (seconds, finite) seen by `camera`; `backend` may be null.
    const ActorFrameStatistics& processFrame(Node& root, const Camera& camera, double time, DrawBackend* backend = nullptr);

    /// The draw list of the last frame.
    const DrawList& drawList() const;
    /// Statistics of the last frame.
    const ActorFrameStatistics& statistics() const { return stats_; }

private:
    // One actor reaching CULL 1, and what the cascade found.
    struct Candidate {
        ActorId id;
        const Node* node;
        std::uint32_t member;
        PlaneMask mask;          // planes still crossed after the last test
        std::uint8_t pending;    // 1: a group member whose Refpoint Bsphere is still to be tested
    };

    // ActorTraversal: actor processing's handling of Actor and ActorGroup nodes.
    BoundingSphere bound(Node& node, std::span<const ActorId> ids, MatrixBoundsVisitor& visitor) override;
    void cull(Node& node, std::span<const ActorId> ids, CullVisitor& visitor) override;
    void culledOut(Node& node, std::span<const ActorId> ids, CullVisitor& visitor) override;

    void processActors(Node& root, const Camera& camera, double time, DrawBackend* backend);
    void cullRefpoints(const Frustum& frustum, const Vec3& eye);  // phase 2 for group members
    // Calls body(begin, end) over [0, n): on the pool when there is one and nothing is counted.
    void forRanges(std::size_t n, bool counting, const std::function<void(std::size_t, std::size_t)>& body);

    Crowd& crowd_;
    TraditionalProcessor traditional_;
    std::unique_ptr<WorkerPool> pool_;
    Processing processing_ = Processing::Actor;
    double lodScale_ = 1.0;
    bool skeletalLod_ = true;
    bool behaviouralLod_ = true;
    std::optional<Frustum> cullingFrustum_;
    std::uint64_t frame_ = 0;
    double lastTime_ = 0.0;
    ActorFrameStatistics stats_;
    DrawList drawList_;

    // Per-frame workspace (reused; grows only).
    std::vector<Candidate> candidates_;
    std::vector<float> cx_, cy_, cz_, cr_;
    std::vector<Containment> containment_;
    std::vector<std::size_t> survivors_;        // indices into candidates_
    std::vector<double> detail2_;               // per survivor: squared detail distance
    std::vector<int> level_;                    // per survivor: behavioural level
    std::vector<std::uint32_t> nodeBase_;       // per survivor: first entry in the per-node arrays
    std::vector<std::uint32_t> evaluated_;      // per survivor: Skeleton nodes evaluated
    std::vector<std::uint8_t> active_;          // per node of each survivor
    std::vector<std::uint8_t> visible_;         // per part of each survivor (nodes, root, held)
    std::vector<Affine> model_;
    std::vector<BoundingSphere> geometry_, subtree_;
    std::vector<PlaneMask> masks_;
};

}  // namespace throng
