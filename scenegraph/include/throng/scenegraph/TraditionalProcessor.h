#pragma once
// Traditional processing (DESIGN.md, "One frame, two ways"), the baseline every benchmark compares
// against: APP runs every callback, every matrix is composed on the CPU, bounds are recomputed
// bottom-up, CULL tests them with plane masks, each LOD node computes its own distance, then DRAW.

#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/FrameStatistics.h"
#include "throng/scenegraph/OcclusionCulling.h"
#include "throng/scenegraph/OpCounter.h"

#include <array>
#include <optional>

namespace throng {

class Camera;
class DrawBackend;
class Node;

/// Runs APP / matrices-and-bounds / CULL / DRAW on a tree, one frame at a time.
class TraditionalProcessor {
public:
    /// Sets the LOD scale (distance multiplier; > 1 lowers detail sooner). Must be finite and > 0.
    void setLodScale(double scale);
    /// Forces every matrix and bound to be recomputed every frame (no temporal coherence).
    void setFullRecompute(bool full) { fullRecompute_ = full; }
    /// Culls against `frustum` instead of the camera's (null restores the camera's).
    void setCullingFrustum(std::optional<Frustum> frustum) { cullingFrustum_ = frustum; }
    /// Culls nodes hidden behind the scene's Occluder nodes too, with a buffer of `settings`
    /// (null, the default: no occlusion culling, nothing built). Throws std::invalid_argument for
    /// bad settings.
    void setOcclusion(const std::optional<OcclusionSettings>& settings);
    /// The occlusion stage, or null when occlusion culling is off.
    const OcclusionCulling* occlusion() const { return occlusion_ ? &*occlusion_ : nullptr; }
    /// The operation counter (disabled until counter().setEnabled(true)).
    OpCounter& counter() { return counter_; }

    /// Processes one frame at simulation time `time` (seconds; must be finite) seen by `camera`.
    /// `backend` may be null to stop after CULL. Returns the frame's statistics.
    const FrameStatistics& processFrame(Node& root, const Camera& camera, double time,
                                        DrawBackend* backend = nullptr);

    /// The draw list of the last frame. Double-buffered: it stays valid, untouched, through the
    /// next processFrame() call, so DRAW of frame N may run while frame N+1 is processed.
    const DrawList& drawList() const { return drawLists_[current_]; }
    /// Statistics of the last frame.
    const FrameStatistics& statistics() const { return stats_; }

private:
    OpCounter counter_;
    std::array<DrawList, 2> drawLists_;  // this frame's and the previous one's
    std::size_t current_ = 0;
    FrameStatistics stats_;
    std::optional<Frustum> cullingFrustum_;
    std::optional<OcclusionCulling> occlusion_;
    double lodScale_ = 1.0;
    double lastTime_ = 0.0;
    std::uint64_t frame_ = 0;
    bool fullRecompute_ = false;
};

}  // namespace throng
