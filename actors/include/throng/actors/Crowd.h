#pragma once
// The actors of a scene, stored as flat arrays (structure of arrays) so that the culling cascade
// walks them without chasing pointers. Clones share their template (skeleton description, clips,
// geometry); only per-actor state lives here: Reference Point and Skeleton Root transforms, bounding
// spheres, eye distance, priority, tint, DOF values. Actor and ActorGroup nodes put actors into a
// scenegraph.

#include <cstdint>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "throng/actors/ActorId.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/actors/Affine.h"
#include "throng/actors/Behaviour.h"
#include "throng/actors/PagedArray.h"
#include "throng/actors/RootPose.h"
#include "throng/actors/detail/PoseBatch.h"
#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/FrameContext.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/MatrixBoundsVisitor.h"
#include "throng/scenegraph/OpCounter.h"

namespace throng {

class Actor;
class ActorGroup;
class Drawable;
class Node;

/// How one actor looks and how much detail it deserves.
struct ActorLook {
    /// Detail priority (seed 002 §5): LOD distances are divided by it, so 2 keeps detail twice as
    /// far and 0.5 drops it at half the distance. Must be positive.
    float priority = 1.0f;
    glm::vec4 tint{1.0f};  ///< colour multiplier for this clone
    BodyLook body;         ///< its colours per body region (templates whose meshes have regions)
};

/// An object an actor holds (seed 002 §4.3): drawn in a Skeleton node's frame.
struct HeldObject {
    int node = 0;                               ///< the node holding it (for example a hand)
    std::shared_ptr<const Drawable> drawable;   ///< what is held
};

/// Where an actor stood in the culling cascade in the last frame (seed 002 Table 2).
enum class ActorClass : std::uint8_t {
    NotInScene,       ///< no node holds it: simulated, never drawn
    CulledWithGroup,  ///< a generic group above it was outside
    A,                ///< Refpoint Bsphere outside
    B,                ///< Refpoint Bsphere inside
    C1,               ///< Refpoint crosses, Sklsroot Bsphere outside
    C2,               ///< Refpoint crosses, Sklsroot Bsphere inside
    C3_1,             ///< Sklsroot crosses, internal spheres wholly in or out
    C3_2,             ///< Sklsroot crosses, internal spheres need culling
    Occluded,         ///< hidden behind occluders (its group's, Refpoint or Sklsroot Bsphere)
};

/// All actors of a scene. It must outlive the Actor and ActorGroup nodes made from it.
class Crowd {
public:
    /// Per-actor state, one entry per ActorId (for processors and nodes; users read it through
    /// the accessors below).
    struct State {
        std::vector<const ActorTemplate*> tmpl;     ///< template of each actor
        std::vector<Behaviour*> behaviour;          ///< its behaviour
        std::vector<std::uint32_t> slot;            ///< its slot in the behaviour
        PagedArray<Mat4> refLocal;                  ///< Reference Point in the parent frame
        PagedArray<Mat4> refWorld;                  ///< Reference Point in the world
        std::vector<BoundingSphere> refSphereLocal; ///< Refpoint Bsphere, Reference Point frame
        PagedArray<BoundingSphere> refSphereWorld;  ///< Refpoint Bsphere, world
        PagedArray<RootPose> root;                  ///< Skeleton Root relative to the Reference Point
        PagedArray<Mat4> sklsWorld;                 ///< Skeleton Root in the world
        std::vector<double> sklsRadius;             ///< Sklsroot Bsphere radius
        std::vector<double> eyeDistance;            ///< distance eye - Skeleton Root (infinite if not computed)
        std::vector<float> priority;                ///< detail priority
        std::vector<glm::vec4> tint;                ///< colour multiplier
        std::vector<BodyLook> body;                 ///< colours per body region
        std::vector<std::uint32_t> dofOffset;       ///< first DOF value in `dofs`
        PagedArray<float> dofs;                     ///< DOF values of every actor
        std::vector<std::uint32_t> nodeOffset;      ///< first Skeleton node entry in per-node workspaces
        std::vector<Node*> owner;                   ///< the node that holds the actor, or null
        std::vector<std::uint32_t> member;          ///< its index within that node
        std::vector<std::int32_t> held;             ///< index into heldObjects, or -1
        std::vector<ActorClass> actorClass;         ///< classification in the last frame
        std::vector<std::uint8_t> present;          ///< 1 when its state is this step's (Behaviour::presence), as of phase 1
        /// 1 once the per-frame arrays above that are PagedArrays hold the actor's values; 0 while
        /// they are deferred (Crowd::deferStateUntilShown): unwritten, read as zero bytes.
        std::vector<std::uint8_t> stateWritten;
        std::vector<std::vector<HeldObject>> heldObjects;  ///< held objects, per actor that holds any
        std::uint32_t totalNodes = 0;               ///< sum of the actors' Skeleton node counts
    };

    /// Workspace of traditional processing: every actor's Skeleton node matrices and spheres,
    /// computed on the CPU each frame. Allocated only when traditional processing runs.
    struct TraditionalWorkspace {
        std::vector<Affine> model;                   ///< node to Skeleton Root
        std::vector<Mat4> world;                     ///< node to world
        std::vector<BoundingSphere> geometry;        ///< geometry spheres, world
        std::vector<BoundingSphere> subtree;         ///< subtree spheres, world
        std::vector<BoundingSphere> whole;           ///< per actor: all its internal spheres, world
        /// What one chunk of a parallel loop produced, joined in chunk order.
        struct Chunk {
            OpCounter ops;                           ///< FMULT tallies (enabled when counting)
            DrawSegment* items = nullptr;            ///< where its draw items go (CULL only)
            BoundingSphere bound;                    ///< union of the chunk's actors' bounds
            std::vector<PlaneMask> masks;            ///< scratch: plane mask per node while culling
            MatrixBoundsStatistics matrices;         ///< matrix and sphere work
            std::uint64_t spheresTested = 0;         ///< sphere-frustum tests
            std::uint64_t lodDistances = 0;          ///< eye distances computed by LOD nodes
            detail::PoseBatchWorkspace pose;         ///< scratch of the pose batches
        };
        std::vector<Chunk> chunks;                   ///< one per chunk of the current loop
    };

    Crowd();
    ~Crowd();
    Crowd(const Crowd&) = delete;
    Crowd& operator=(const Crowd&) = delete;

    /// Adds an actor of template `tmpl` driven by `behaviour` (its slot `slot` was obtained from the
    /// behaviour). Throws std::invalid_argument if a pointer is null or the priority is not positive.
    ActorId add(std::shared_ptr<const ActorTemplate> tmpl, std::shared_ptr<Behaviour> behaviour,
                std::uint32_t slot, const ActorLook& look = {});
    /// Number of actors.
    std::size_t size() const { return state_.tmpl.size(); }
    /// Actors held by a node of a scene (ActorClass other than NotInScene), kept as nodes take and
    /// release them.
    std::size_t actorsInScene() const { return inScene_; }
    /// The behaviours driving the actors, in order of their first actor.
    std::span<const std::shared_ptr<Behaviour>> behaviours() const { return behaviours_; }
    /// The actor of each slot of behaviours()[b] (kNoActor where no actor drives that slot), in
    /// slot order.
    std::span<const ActorId> actorsBySlot(std::size_t b) const { return actorsBySlot_[b]; }

    /// A node standing for actor `id`, to put in a scenegraph. Throws std::invalid_argument if the
    /// id is out of range or the actor already belongs to a node.
    std::shared_ptr<Actor> makeActorNode(ActorId id);
    /// A node standing for many actors culled together first (a crowd or flock group). Throws as
    /// makeActorNode for any of them.
    std::shared_ptr<ActorGroup> makeGroupNode(std::vector<ActorId> ids);

    /// Makes actor `id` hold `object`: both of its static spheres grow to keep enclosing it (seed
    /// 002 §4.3). Throws std::invalid_argument on a bad id, node or null drawable.
    void hold(ActorId id, HeldObject object);
    /// Sets an actor's detail priority (positive).
    void setPriority(ActorId id, float priority);

    /// From now on, actors added get no per-frame state (transforms, world spheres, DOF values)
    /// until they are first present: a process that shows only its share of a scene's actors (a
    /// rank posing the walkers it steps) then takes no memory for the others'. Phase 1 writes the
    /// state of the actors it visits (writeState); until then the accessors below read an actor's
    /// initial values. Processing that reads every actor must call writeAllStates first.
    void deferStateUntilShown() { deferring_ = true; }
    /// Writes actor `id`'s initial per-frame state if it was deferred.
    void writeState(ActorId id) {
        if (!state_.stateWritten[id]) writeInitialState(id);
    }
    /// Writes every deferred actor's initial per-frame state.
    void writeAllStates();
    /// Actors whose per-frame state is still deferred.
    std::size_t deferredStates() const { return deferred_; }

    /// The actor's template.
    const ActorTemplate& templateOf(ActorId id) const { return *state_.tmpl[id]; }
    /// Its Reference Point in the world, as of the last frame.
    const Mat4& referencePoint(ActorId id) const { return state_.stateWritten[id] ? state_.refWorld[id] : kIdentity; }
    /// Its Skeleton Root in the world, as of the last frame it was visible.
    const Mat4& skeletonRoot(ActorId id) const { return state_.stateWritten[id] ? state_.sklsWorld[id] : kIdentity; }
    /// Refpoint Bsphere in the world, as of the last frame.
    const BoundingSphere& refpointSphere(ActorId id) const {
        return state_.stateWritten[id] ? state_.refSphereWorld[id] : kNoSphere;
    }
    /// Radius of the Sklsroot Bsphere.
    double skeletonRootRadius(ActorId id) const { return state_.sklsRadius[id]; }
    /// Eye distance computed in the last frame (infinite when the actor was culled before it).
    double eyeDistance(ActorId id) const { return state_.eyeDistance[id]; }
    /// Classification in the last frame.
    ActorClass actorClass(ActorId id) const { return state_.actorClass[id]; }
    /// DOF values of the actor (as of the last frame they were evaluated).
    std::span<const float> dofs(ActorId id) const;

    /// Bytes of state one more clone of `tmpl` adds (its template is shared).
    std::size_t bytesPerActor(const ActorTemplate& tmpl) const;

    /// Per-actor state, for processors and nodes.
    State& state() { return state_; }
    /// Per-actor state, read-only.
    const State& state() const { return state_; }
    /// Traditional processing's workspace, sized for every actor on first use.
    TraditionalWorkspace& traditionalWorkspace();
    /// Advances the simulation once: every behaviour's shared state (navigation, flocking, gaze)
    /// steps to `context.time`. The frame loop calls it once per frame, before APP and CULL;
    /// nothing else advances the simulation, so every processor of a frame sees the same state.
    /// Throws std::invalid_argument if the time is not finite or goes backwards.
    void step(const FrameContext& context);
    /// Milliseconds the last step() took.
    double lastStepMs() const { return lastStepMs_; }
    /// Steps taken so far.
    std::uint64_t steps() const { return steps_; }
    /// Simulation time of the last step (0 before the first).
    double time() const { return time_; }
    /// The nodes standing for this crowd's actors (Actor and ActorGroup): in creation order until a
    /// node is destroyed, which moves the last one into its place.
    std::span<Node* const> nodes() const { return nodes_; }
    /// Called by a node being destroyed: its actors stay in the crowd, held by no node.
    void release(Node* node, std::span<const ActorId> ids);

private:
    void claim(ActorId id, Node* owner, std::uint32_t member, const char* who);
    void writeInitialState(ActorId id);

    static inline const Mat4 kIdentity{1.0};
    static inline const BoundingSphere kNoSphere{};

    State state_;
    TraditionalWorkspace traditional_;
    std::vector<std::shared_ptr<const ActorTemplate>> templates_;
    std::vector<std::shared_ptr<Behaviour>> behaviours_;
    std::vector<std::vector<ActorId>> actorsBySlot_;  // per behaviour, per slot: its actor
    std::size_t inScene_ = 0;                         // actors with an owner
    std::size_t deferred_ = 0;                        // actors whose per-frame state is unwritten
    bool deferring_ = false;                          // actors added now defer theirs
    std::vector<Node*> nodes_;
    std::unordered_map<const Node*, std::size_t> nodeSlot_;  // where each node is in nodes_ (release in O(1))
    double time_ = 0.0;
    double lastStepMs_ = 0.0;
    std::uint64_t steps_ = 0;
};

}  // namespace throng
