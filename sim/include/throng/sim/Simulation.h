#pragma once
// A scene file's world, built and ready to step: the town and its navigation mesh, the actor
// templates, the actors with their behaviours, and the effects the file declares — only those.
// Problems found while building (a clip that does not exist, a glTF file that does not load)
// are SceneErrors naming the JSON path they come from.

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "throng/actors/Crowd.h"
#include "throng/scenegraph/FrameContext.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/CameraPath.h"
#include "throng/sim/EffectCounters.h"
#include "throng/sim/FaceLayer.h"
#include "throng/sim/NavMesh.h"
#include "throng/sim/SceneDescription.h"
#include "throng/sim/SimulationClock.h"
#include "throng/sim/TownLayout.h"

namespace throng {
class ActorProcessor;
class LOD;
}

namespace throng::sim {

class Locomotion;
class Ranks;

/// Reports a long build's progress: the stage and how far it is, in [0, 1].
using BuildProgress = std::function<void(const std::string& stage, double fraction)>;

/// Everything a scene file asked for.
class Simulation {
public:
    /// A template in use and the clip its actors mostly show (walk, idle or flap): the clip
    /// impostors of it are baked from. A template that walks in one group and stands in another
    /// is loaded twice, so that each copy has one main clip.
    struct TemplateInUse {
        std::string name;                           ///< as declared (with "#idle" for a standing copy)
        std::shared_ptr<const ActorTemplate> tmpl;  ///< the template
        int clip = 0;                               ///< its main clip
    };

    /// One group of actors the file declared.
    struct ActorGroupInfo {
        std::string name;              ///< as declared
        std::string behaviour;         ///< walk, idle or flight
        std::vector<ActorId> actors;   ///< its actors in the crowd
    };

    /// How much of a scene a process builds.
    enum class Scope {
        /// Everything: the town's scene graph, every actor in the crowd with its behaviours and effects.
        Everything,
        /// What stepping the walkers needs, for a rank that draws nothing: the navigation mesh (the
        /// one given, else built from the town's tiles with no scene graph made of them), the
        /// walkers' templates and their Locomotion. No crowd, no standing people, flocks, gaze or
        /// faces; groups list no actors.
        Walkers,
        /// What a rank posing the walkers it steps needs (distribute with posedWhereStepped): the
        /// navigation mesh (as for Walkers) and every actor group with its node, templates and
        /// effects, but no scene graph of the town. The actors of groups that do not walk stand
        /// in, absent (ElsewhereBehaviour), so that the crowd's actors, nodes and templates are
        /// numbered as in the whole world; only the walkers step.
        Actors,
    };

    /// How to build a world.
    struct BuildOptions {
        Scope scope = Scope::Everything;  ///< all of it, or what stepping the walkers needs
        /// The navigation mesh this scene builds, made by another process (rank 0's, sent to the
        /// others): used as it is instead of being built again. Null: built here.
        std::shared_ptr<const NavMesh> navMesh;
    };

    /// Builds the world of `description` (all of it, or for Scope::Walkers what a rank stepping
    /// walkers needs: the walkers are placed as in the whole world, slot for slot). Throws
    /// SceneError (with the JSON path), std::runtime_error (a navigation mesh that cannot be built)
    /// or std::invalid_argument (a given navigation mesh built with other settings than the scene's).
    static std::unique_ptr<Simulation> build(SceneDescription description, const BuildProgress& progress, BuildOptions options);
    /// Builds the whole world of `description` (Scope::Everything, its own navigation mesh).
    static std::unique_ptr<Simulation> build(SceneDescription description, const BuildProgress& progress = {});
    ~Simulation();
    Simulation(const Simulation&) = delete;
    Simulation& operator=(const Simulation&) = delete;

    /// Advances the world by one fixed step (the first call starts it at time 0) and returns that
    /// frame's context. The frame loop calls it once per frame, before APP and CULL; nothing else
    /// advances the simulation, so every processor and renderer of the frame sees the same state.
    /// Per-agent work runs on the threads set by setThreads.
    const FrameContext& step();
    /// The context of the last step (time 0, frame 0 before the first).
    const FrameContext& now() const { return now_; }
    /// Milliseconds the last step took.
    double lastStepMs() const { return walkersOnly_ ? walkersOnlyMs_ : crowd_.lastStepMs(); }
    /// Threads of the step's per-agent work (default 1). Results do not depend on it. Throws
    /// std::invalid_argument for 0.
    void setThreads(unsigned threads);

    /// Steps the walkers' regions split over the ranks of the run (see Locomotion::distribute):
    /// every rank builds the world of one scene (rank 0 all of it, the others Scope::Walkers is
    /// enough) and calls step() as often, and rank 0's world is then that of one process; the other
    /// ranks step their walkers only. Call before the first step; `ranks` must outlive the stepping.
    /// Throws std::logic_error after the first step, or on rank 0 of a world built for walkers only.
    /// With `posedWhereStepped`, on every rank: each rank poses the walkers it steps
    /// (Locomotion::setPosedWhereStepped), the ranks other than 0 in a world of Scope::Actors (or
    /// Everything), stepping the walkers and their effects (gaze, faces); a world of Scope::Walkers
    /// there is then a std::logic_error.
    void distribute(Ranks& ranks, bool posedWhereStepped = false);
    /// Distributed, on rank 0, before step(): the frustum the coming frame will cull against. The
    /// other ranks then send only the walkers that could pass CULL 1 or be looked at by one that
    /// does (Locomotion::setGatherView, with a margin from the walkers' Refpoint Bspheres and the
    /// gaze range); the rest, rank 0's own walkers included, are absent this frame. Only those
    /// within shownMargin() may be seen: the cascade skips every other walker unread, so rank 0's
    /// APP and CULL grow with the walkers in view, not with those it simulates or knows of. Null:
    /// every walker is sent (what a recorder of every actor needs). No effect unless distributed.
    void setGatherView(std::optional<Frustum> view);
    /// Metres beyond the view within which walkers are still sent (see setGatherView).
    double gatherMargin() const { return gatherMargin_; }
    /// Metres beyond the view within which a walker may be seen: how far its Refpoint Bsphere
    /// reaches from where it stands, and a metre to spare (CULL 1 then finds the others outside).
    double shownMargin() const { return shownMargin_; }

    /// The scene graph: the town's tiles and one node per actor group.
    Group& root() { return *root_; }
    /// The actors.
    Crowd& crowd() { return crowd_; }
    /// The actors, read-only.
    const Crowd& crowd() const { return crowd_; }
    /// Construction and tick counts of every effect.
    const EffectCounters& effects() const { return effects_; }
    /// The face layers (walkers', standing people's) when the scene declares faces, blinks or
    /// phrases; empty otherwise. For captions (FaceLayer::speechAt) and the faces' cost.
    const std::vector<std::shared_ptr<FaceLayer>>& faceLayers() const { return faceLayers_; }
    /// What was built.
    const SceneDescription& description() const { return description_; }
    /// How much of it was built.
    Scope scope() const { return scope_; }
    /// The camera path.
    const CameraPath& camera() const { return *camera_; }
    /// The walkers' locomotion (its regions, ghosts and handovers), or null when nothing walks.
    const Locomotion* locomotion() const { return walkers_.get(); }
    /// The same, to keep what a walker carries (Locomotion::setCarried).
    Locomotion* locomotion() { return walkers_.get(); }
    /// The navigation mesh, or null when nothing walks.
    const NavMesh* navMesh() const { return nav_.get(); }
    /// The same, shared (for another world built from the same scene: BuildOptions::navMesh).
    std::shared_ptr<const NavMesh> sharedNavMesh() const { return nav_; }
    /// The town's layout, or null when there is none.
    const TownLayout* town() const { return town_ ? &*town_ : nullptr; }
    /// The actor groups, in file order.
    std::span<const ActorGroupInfo> groups() const { return groups_; }
    /// The templates in use, each with its main clip.
    std::span<const TemplateInUse> templates() const { return templates_; }
    /// New key-pose caches for the templates the scene's representation/keyPoseCache names (one per
    /// template in use of that name; none when the scene declares no cache). Each call builds a
    /// fresh set, since a cache serves one processor. Throws SceneError naming the template if it
    /// cannot be cached (no skinned mesh, rigid parts).
    std::vector<std::shared_ptr<KeyPoseCache>> makeKeyPoseCaches();
    /// Gives `processor` fresh caches (makeKeyPoseCaches) and the scene's band: from the declared
    /// distance, with the representation's hysteresis. Nothing when the scene declares no cache.
    /// Throws as makeKeyPoseCaches.
    void attachKeyPoseCaches(ActorProcessor& processor);
    /// Multiplies the distances of the town's LOD levels on top of any LOD scale (LOD::
    /// setDistanceScale on every tile's LOD node; the scene's town/lodScale at build, else 1).
    /// No effect on a town built without levels. Call between frames. Throws std::invalid_argument
    /// unless finite and > 0.
    void setTownLodScale(double scale);
    /// The town's LOD distance multiplier (1 unless set).
    double townLodScale() const { return townLodScale_; }
    /// Whether the town was built with LOD levels.
    bool townHasLod() const { return !townLods_.empty(); }
    /// Triangles of the town's tiles.
    std::uint64_t townTriangles() const { return townTriangles_; }

private:
    Simulation() = default;
    void buildTown(const BuildProgress& progress);
    void buildActors(const BuildProgress& progress, std::shared_ptr<const NavMesh> given);

    SceneDescription description_;
    EffectCounters effects_;
    Crowd crowd_;  // before the nodes: they hand their actors back when destroyed
    std::shared_ptr<Group> root_;
    std::optional<TownLayout> town_;
    std::shared_ptr<const NavMesh> nav_;
    std::unique_ptr<CameraPath> camera_;
    std::vector<ActorGroupInfo> groups_;
    std::vector<TemplateInUse> templates_;
    std::vector<std::shared_ptr<Behaviour>> behaviours_;
    std::vector<std::shared_ptr<FaceLayer>> faceLayers_;
    std::shared_ptr<Locomotion> walkers_;
    NavGeometry navGeometry_;
    std::unique_ptr<SimulationClock> clock_;
    std::unique_ptr<ThreadTeam> team_;
    FrameContext now_;
    bool started_ = false;
    Scope scope_ = Scope::Everything;
    bool navGiven_ = false;        // BuildOptions::navMesh was given: the town's tiles are not read for it
    bool walkersOnly_ = false;     // distributed, on a rank other than 0: steps its walkers only
    double walkersOnlyMs_ = 0.0;
    double gatherMargin_ = 0.0;  // setGatherView's margin, from the walkers and the gaze range
    double shownMargin_ = 0.0;   // setGatherView's shown margin, from the walkers' Refpoint Bspheres
    std::uint64_t townTriangles_ = 0;
    std::vector<std::shared_ptr<LOD>> townLods_;  // every tile's LOD node (town LOD declared)
    double townLodScale_ = 1.0;
};

}  // namespace throng::sim
