#pragma once
// Processes a scene holding actors one frame at a time, by traditional processing or by actor
// processing (seed 002 §4.2), on the very same scene:
//   1. Reference Points of all actors (simulation state, whatever the camera);
//   2. CULL 1: Refpoint Bspheres (after generic groups above them) - rejects A; then, when the
//      scene declares occluders and occlusion is on, the survivors' Refpoint Bspheres against the
//      frame's occlusion buffer (cells of nearby actors first) - rejects the hidden;
//   3. Skeleton Roots of the survivors;
//   4. CULL 2: Sklsroot Bspheres - rejects C1, then the hidden; one eye distance per actor;
//      impostor and key-pose cache tiers (the cache's poses chosen for the frame); skeletal LOD;
//   5. behaviour of the active Skeleton nodes at the actor's behavioural level, and their matrices;
//   6. CULL 3: internal spheres, only for actors whose Sklsroot Bsphere crosses a plane;
//   7. the draw list, each part at its vaLod level.
// Generic nodes of the scene are processed as TraditionalProcessor does in both methods. Each phase
// is a job (throng/actors/cascade/) that declares what it reads and writes and validates itself;
// the processor runs them in order over one workspace it keeps between frames.

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "throng/actors/ActorFrameStatistics.h"
#include "throng/actors/ActorId.h"
#include "throng/actors/ActorTraversal.h"
#include "throng/actors/Affine.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/OcclusionCulling.h"
#include "throng/scenegraph/TraditionalProcessor.h"

namespace throng {

class ActorTemplate;
class Camera;
class Crowd;
class DrawBackend;
class Drawable;
class KeyPoseArbiter;
class KeyPoseCache;
class Node;
class ThreadTeam;
namespace cascade {
struct CascadeFrame;
struct PresentMembers;
}

/// Frame processor for scenes with actors of one Crowd.
class ActorProcessor : private ActorTraversal {
public:
    /// Processes scenes whose actors live in `crowd` (which must outlive the processor).
    explicit ActorProcessor(Crowd& crowd);
    ~ActorProcessor() override;

    /// Chooses the method (default: actor processing).
    void setProcessing(Processing processing) { processing_ = processing; }
    /// The method in use.
    Processing processing() const { return processing_; }
    /// LOD scale (distance multiplier, > 0; above 1 lowers detail sooner).
    void setLodScale(double scale);
    /// The LOD scale in use.
    double lodScale() const { return lodScale_; }
    /// Switches skeletal LOD (actor processing): off, every Skeleton node is processed.
    void setSkeletalLod(bool on) { skeletalLod_ = on; }
    /// Switches behavioural LOD (actor processing): off, behaviours always run at level 0.
    void setBehaviouralLod(bool on) { behaviouralLod_ = on; }
    /// Whether behavioural LOD is on.
    bool behaviouralLod() const { return behaviouralLod_; }
    /// Hybrid LOD (actor processing): beyond `distance` metres (scaled by the LOD scale and the
    /// actor's priority, like every LOD distance) an actor whose template has an impostor is drawn
    /// as one item showing it, placed at its Reference Point, and none of its Skeleton nodes is
    /// processed (the seed's "LOD formed by none"). An actor becomes an impostor beyond
    /// distance + hysteresis and gets its geometry back within distance - hysteresis, so actors
    /// near the threshold do not flicker. Distance 0 (the default) turns impostors off. Throws
    /// std::invalid_argument for negative or non-finite values.
    void setImpostorDistance(double distance, double hysteresis = 0.0);
    /// The impostor distance (0: off).
    double impostorDistance() const { return impostorDistance_; }
    /// The impostor hysteresis, metres.
    double impostorHysteresis() const { return impostorHysteresis_; }
    /// Shows actors of `tmpl` beyond the impostor distance as `impostor` (null removes it). The
    /// drawable must outlive its use; the backend knows how to draw it (throng::render's
    /// ImpostorDrawable).
    void setImpostor(const ActorTemplate& tmpl, std::shared_ptr<const Drawable> impostor);
    /// The impostor shown for actors of `tmpl`, or null.
    const Drawable* impostorOf(const ActorTemplate& tmpl) const {
        for (const auto& [t, impostor] : impostors_)
            if (t == &tmpl) return impostor.get();
        return nullptr;
    }
    /// What this processor keeps of one actor between frames: the side of each hysteresis band it
    /// was last on (impostor, key-pose cache).
    struct ActorTiers {
        std::uint8_t impostor = 0;  ///< 1 while drawn as an impostor
        std::uint8_t keyPose = 0;   ///< 1 while in the key-pose band
        /// Both equal.
        bool operator==(const ActorTiers&) const = default;
    };
    /// Actor `id`'s tiers as the last frame left them (zeros for an actor never shown). A process
    /// that takes an actor over from another (ranks, as walkers cross between them) sets them
    /// there (setTiers), so that the actor crosses a band's threshold where one process would.
    ActorTiers tiersOf(ActorId id) const {
        return {id < impostorTier_.size() ? impostorTier_[id] : std::uint8_t{0}, id < keyPoseTier_.size() ? keyPoseTier_[id] : std::uint8_t{0}};
    }
    /// Sets actor `id`'s tiers (see tiersOf). Throws std::invalid_argument for an id the crowd lacks
    /// or a tier other than 0 or 1.
    void setTiers(ActorId id, ActorTiers tiers);
    /// Whether actor `id` was drawn as an impostor in the last frame.
    bool drawnAsImpostor(ActorId id) const { return id < impostorTier_.size() && impostorTier_[id] != 0; }
    /// Key-pose caches (seed 004): an actor nearer than the impostor distance but beyond `distance`
    /// metres (scaled like every LOD distance; entering beyond distance + hysteresis, leaving
    /// within distance - hysteresis), whose template has a cache and whose behaviour plays a main
    /// clip, is drawn from its template's cache when the key-poses it needs are held: no Skeleton
    /// node is processed for it. The others are posed and skinned as usual. Distance 0 (the
    /// default) turns caches off. Throws std::invalid_argument for negative or non-finite values.
    void setKeyPoseDistance(double distance, double hysteresis = 0.0);
    /// The key-pose distance (0: off).
    double keyPoseDistance() const { return keyPoseDistance_; }
    /// The key-pose hysteresis, metres.
    double keyPoseHysteresis() const { return keyPoseHysteresis_; }
    /// Gives `cache`'s template that cache (replacing the one it had). A cache serves one processor
    /// (its rows are this processor's state). Throws std::invalid_argument if `cache` is null.
    void setKeyPoseCache(std::shared_ptr<KeyPoseCache> cache);
    /// When several processes each show some actors of one crowd (ranks posing their own walkers):
    /// `arbiter` settles the caches' rows over every process's demands each frame, so that every
    /// process draws from the rows one process showing every actor would hold. Null (the default):
    /// this processor selects for its own actors. The arbiter must outlive its use.
    void setKeyPoseArbiter(KeyPoseArbiter* arbiter) { keyPoseArbiter_ = arbiter; }
    /// Removes every key-pose cache.
    void clearKeyPoseCaches();
    /// The key-pose caches.
    const std::vector<std::shared_ptr<KeyPoseCache>>& keyPoseCaches() const { return keyPoseCaches_; }
    /// Occlusion culling with a buffer of `settings` (null, the default: off, nothing built), in
    /// both methods: the scene's Occluder nodes are drawn each frame, generic nodes and actor
    /// groups are tested during the traversal, actors after CULL 1 and CULL 2. Throws
    /// std::invalid_argument for bad settings.
    void setOcclusion(const std::optional<OcclusionSettings>& settings);
    /// For a process that tests against an occlusion buffer another process drew (ranks posing
    /// their own actors; actor processing): the next frames test generic nodes, actor groups and
    /// actors against `buffer` as against one drawn here, and draw none of their own. Null (the
    /// default): this processor's own occlusion stage, if any. The buffer must hold the frame's
    /// occluders (OcclusionBuffer::read) whenever processFrame runs.
    void setSharedOcclusionBuffer(const OcclusionBuffer* buffer) { sharedOcclusion_ = buffer; }
    /// Called by actor processing once per frame, after the occlusion stage and before CULL, with
    /// the buffer CULL will test against (null when occlusion is off or rests this frame): a
    /// drawing process sends it there to the processes posing their own actors, which must test
    /// against it before CULL 2 needs them (the key-pose arbiter). Empty (the default): none.
    void setBeforeCull(std::function<void(const OcclusionBuffer*)> beforeCull) { beforeCull_ = std::move(beforeCull); }
    /// When this processor's frames are one share of several processes' (ranks posing their own
    /// actors): its occlusion stage decides whether to rest from the counts of every share, given
    /// to settleOcclusion() after each frame, not from its own. Off by default.
    void setOcclusionSettledByShares(bool shares) { occlusionByShares_ = shares; }
    /// With setOcclusionSettledByShares: the last frame's statistics, every process's share added
    /// (addShare). Nothing unless that frame built an occlusion buffer here.
    void settleOcclusion(const ActorFrameStatistics& whole);
    /// The occlusion stage of actor processing, or null when occlusion is off.
    const OcclusionCulling* occlusion() const { return occlusion_ ? &*occlusion_ : nullptr; }
    /// Culls against `frustum` instead of the camera's (null restores the camera's).
    void setCullingFrustum(std::optional<Frustum> frustum);
    /// Runs the per-actor work of both methods on `threads` threads (default 1): every phase of
    /// the cascade, and traditional processing's behaviours, matrices, spheres and culling. Work is
    /// cut into fixed chunks joined in order, so results (FMULT counts included) are bitwise
    /// identical whatever the number. Throws std::invalid_argument for 0.
    void setThreads(unsigned threads);
    /// Threads of the per-actor work.
    unsigned threads() const;
    /// Operation counter (disabled until counter().setEnabled(true)); shared by both methods.
    OpCounter& counter() { return traditional_.counter(); }

    /// Processes one frame at `time` (seconds, finite) seen by `camera`: APP and CULL, then DRAW
    /// when `backend` is given. The simulation is not stepped here: the frame loop calls
    /// Crowd::step (or sim::Simulation::step) first, so every processor of a frame sees one state.
    const ActorFrameStatistics& processFrame(Node& root, const Camera& camera, double time, DrawBackend* backend = nullptr);

    /// The draw list of the last frame. Double-buffered: it stays valid, untouched, through the
    /// next processFrame() call, so DRAW of frame N may run while frame N+1 is processed.
    const DrawList& drawList() const;
    /// Statistics of the last frame.
    const ActorFrameStatistics& statistics() const { return stats_; }

private:
    // ActorTraversal: actor processing's handling of Actor and ActorGroup nodes.
    BoundingSphere bound(Node& node, std::span<const ActorId> ids, MatrixBoundsVisitor& visitor, const BoundingSphere& roaming) override;
    void cull(Node& node, std::span<const ActorId> ids, CullVisitor& visitor, bool boundIsMemberSphere) override;
    void culledOut(Node& node, std::span<const ActorId> ids, CullVisitor& visitor) override;

    // This frame's present members of `node` (bound() listed them; only while some actor is absent).
    const cascade::PresentMembers& presentMembersOf(const Node& node);
    void processActors(Node& root, const Camera& camera, double time);
    void processTraditionally(Node& root, const Camera& camera, double time);

    Crowd& crowd_;
    TraditionalProcessor traditional_;
    std::unique_ptr<ThreadTeam> team_;
    Processing processing_ = Processing::Actor;
    double impostorDistance_ = 0.0, impostorHysteresis_ = 0.0;
    std::vector<std::pair<const ActorTemplate*, std::shared_ptr<const Drawable>>> impostors_;
    std::vector<std::uint8_t> impostorTier_;    // per actor: 1 while drawn as an impostor
    double keyPoseDistance_ = 0.0, keyPoseHysteresis_ = 0.0;
    std::vector<std::shared_ptr<KeyPoseCache>> keyPoseCaches_;
    KeyPoseArbiter* keyPoseArbiter_ = nullptr;
    std::vector<std::uint8_t> keyPoseTier_;     // per actor: 1 while in the key-pose band
    double lodScale_ = 1.0;
    bool skeletalLod_ = true;
    bool behaviouralLod_ = true;
    std::optional<Frustum> cullingFrustum_;
    std::optional<OcclusionCulling> occlusion_;
    const OcclusionBuffer* sharedOcclusion_ = nullptr;
    std::function<void(const OcclusionBuffer*)> beforeCull_;
    bool occlusionByShares_ = false;
    bool occlusionBuilt_ = false;  // the last frame built an occlusion buffer here
    std::uint64_t frame_ = 0;
    double lastTime_ = 0.0;
    ActorFrameStatistics stats_;
    std::array<DrawList, 2> drawLists_;         // this frame's and the previous one's
    std::size_t current_ = 0;                   // index of this frame's list
    std::unique_ptr<cascade::CascadeFrame> cascade_;  // the cascade's workspace, reused
};

}  // namespace throng
