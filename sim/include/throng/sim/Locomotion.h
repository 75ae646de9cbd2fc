#pragma once
// People walking a navigation mesh between random destinations, steered by DetourCrowd (with local
// avoidance only when the scene asks for it). The walk clip plays at the rate the actor's speed
// calls for (speed matching) and blends into the run clip as the speed rises. Destinations come
// from each actor's own random stream; the crowd steps once per frame for every actor, whatever
// the camera, so trajectories are view-independent and deterministic.
//
// The ground is divided into fixed regions (a RegionGrid), each stepped by its own DetourCrowd and
// navigation query, in parallel. An agent near a border is seen by the neighbouring region as a
// ghost (a copy of it at the start of the step, which that region never moves); an agent that
// crosses a border is handed over at the end of the step, in order of actor slot. Ghosts and
// handovers are flat records, so that regions owned by other processes exchange them as messages:
// distribute() splits the regions over the ranks of an MPI run, and rank 0 gathers the walkers'
// drawn state after each step: every walker, or, given the view the frame culls against
// (setGatherView), only those near it; the others are not known() there, and only those that
// may be seen are present(). The same layout gives the same trajectories with any number of
// threads or ranks.
//
// Three parts, each with its own file: this class is the walker behaviour (gait, Reference Point,
// pose); the region stepper (sim/src/locomotion/RegionStepper) moves the walkers region by region;
// the rank exchange (sim/src/locomotion/RankExchange) carries the regions' records between ranks.

#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "throng/actors/Behaviour.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/sim/EffectCounters.h"
#include "throng/sim/NavMesh.h"
#include "throng/sim/RegionGrid.h"

namespace throng {
class Stopwatch;
}

namespace throng::sim {

class Ranks;

namespace locomotion {
struct WalkerState;
class RegionStepper;
class RankExchange;
}  // namespace locomotion

/// Navigation-mesh locomotion for many actors.
class Locomotion : public Behaviour {
public:
    /// How walkers keep apart: DetourCrowd's sampled velocities, or ORCA's half-planes (sim/OrcaSolver)
    /// on Detour's path corridors.
    enum class AvoidanceModel { Detour, Orca };
    /// Shared settings.
    struct Settings {
        bool avoidance = false;        ///< local avoidance and separation between agents (an effect of its own)
        float radius = 0.35f;          ///< agent radius, metres
        float height = 1.8f;           ///< agent height, metres
        float maxAcceleration = 6.0f;  ///< m/s^2
        float turnRate = 5.0f;         ///< radians per second the facing may turn
        std::uint64_t seed = 1;        ///< destinations' random seed
        RegionGrid regions;            ///< the regions stepped apart (default: one)
        /// Avoidance: how finely candidate velocities are sampled (DetourCrowd's adaptive sampling),
        /// 0 coarsest and cheapest to 3 finest (Detour's own default); a measured accuracy knob.
        int avoidanceQuality = 3;
        /// Avoidance: how far an agent looks for neighbours, in agent radii (DetourCrowd's collision
        /// query range; also how near a border an agent is seen by the next region as a ghost).
        float neighbourRange = 12.0f;
        /// Avoidance: which model keeps walkers apart (DetourCrowd's or ORCA); the path following is
        /// Detour's in both.
        AvoidanceModel avoidanceModel = AvoidanceModel::Detour;
        /// Random destinations lie within this many metres of where the actor is (each way); 0:
        /// anywhere on the mesh. Large towns need it: DetourCrowd's path corridor holds 256
        /// polygons, and a path across kilometres of town is longer.
        double destinationRange = 0.0;
        /// Regions wholly farther than this from the viewpoint (metres, on the ground) step only once
        /// every `farEvery` steps, over the time since they last stepped, their walkers carried on at
        /// their last velocity in between: an approximation a scene declares (0: never).
        double farDistance = 0.0;
        /// How often far regions step (see farDistance); 1: every step.
        int farEvery = 1;
    };
    /// One rank's share of a step: what it stepped, sent and waited for.
    struct RankStepRecord {
        std::uint64_t agents = 0;          ///< walkers its regions own after the step
        std::uint64_t deferred = 0;        ///< of those, walkers of far regions that did not step
        std::uint64_t ghosts = 0;          ///< ghost records its regions exported
        std::uint64_t ghostsToRanks = 0;   ///< of those, records for a region of another rank
        std::uint64_t handovers = 0;       ///< agents that left its regions
        std::uint64_t handedToRanks = 0;   ///< of those, agents handed to a region of another rank
        std::uint64_t borderBytes = 0;     ///< bytes of ghosts and handovers sent to other ranks
        std::uint64_t stateBytes = 0;      ///< bytes of walker records sent to rank 0
        std::uint64_t sent = 0;            ///< walkers it sent rank 0 (all its own unless a view is set)
        std::uint64_t shown = 0;           ///< of those, walkers that may be seen (the others matter only to them)
        double workMs = 0.0;               ///< milliseconds stepping its regions and walkers
        double waitMs = 0.0;               ///< milliseconds in exchanges with the other ranks
        std::uint64_t peakBytes = 0;       ///< the rank's largest resident memory so far (its whole process)
    };
    /// One actor.
    struct Actor {
        std::shared_ptr<const ActorTemplate> tmpl;  ///< whose clips are played (required)
        int walkClip = 0;              ///< clip played at walking speed
        double walkClipSpeed = 1.4;    ///< speed the walk clip was authored for, m/s
        int runClip = -1;              ///< clip blended in as speed rises, or -1
        double runClipSpeed = 3.5;     ///< speed the run clip was authored for, m/s
        glm::vec3 start{0.0f};         ///< where it starts (moved onto the mesh)
        double speed = 1.4;            ///< preferred speed, m/s
        std::uint64_t stream = 0;      ///< its random stream (for example its index in the scene)
        /// A fixed destination (moved onto the mesh): the actor walks there and stays. Without one
        /// it walks between random destinations drawn from its stream.
        std::optional<glm::vec3> goal;
        /// With a goal: a periodic corridor. A walker that comes within 1 m of the line through its
        /// goal across this vector re-enters one such vector back, velocity kept (walkers do not see
        /// each other across that seam). Zero: none.
        glm::vec3 period{0.0f};
    };

    /// Locomotion on `navMesh`, with the given level bands, counting into `counters` (may be null).
    Locomotion(std::shared_ptr<const NavMesh> navMesh, Settings settings,
               std::vector<double> levelEnds = {60.0, std::numeric_limits<double>::infinity()},
               EffectCounters* counters = nullptr);
    ~Locomotion() override;

    /// Registers an actor before the first frame; returns its slot. Throws std::invalid_argument
    /// if the template or a clip is missing, a speed is not positive, the start is nowhere near the
    /// mesh, or the crowd has already started.
    std::uint32_t addActor(const Actor& actor);
    /// Number of actors.
    std::size_t size() const { return actors_.size(); }
    /// The shared settings.
    const Settings& settings() const { return settings_; }
    /// Where an actor stands (after the last step).
    glm::vec3 position(std::uint32_t slot) const;
    /// Current speed of an actor, m/s.
    double speed(std::uint32_t slot) const;
    /// Where an actor is walking to.
    glm::vec3 destination(std::uint32_t slot) const;
    /// The region that owns an actor (after the first frame; distributed, on ranks other than 0,
    /// known for the walkers this rank steps or handed on).
    std::uint32_t region(std::uint32_t slot) const;
    /// Number of regions.
    std::uint32_t regionCount() const { return settings_.regions.regionCount(); }
    /// Ghosts seen by neighbouring regions in the last step (distributed: on rank 0 all ranks'
    /// total, elsewhere this rank's).
    std::size_t lastGhostCount() const { return lastGhosts_; }
    /// Agents handed over to another region at the end of the last step (counted as ghosts are).
    std::size_t lastHandoverCount() const { return lastHandovers_; }
    /// Walkers of far regions that did not step in the last step (counted as ghosts are).
    std::size_t lastDeferredCount() const { return lastDeferred_; }
    /// Milliseconds the last step of the walkers took (regions, their crowds and gaits; distributed,
    /// this rank's share without the gather).
    double lastAdvanceMs() const { return lastAdvanceMs_; }
    /// Bytes the walkers' step holds: the actors, their moving state and the regions (crowds with their
    /// paths and neighbour grids, the records they exchange); 0 before the first step.
    std::size_t stepBytes() const;
    /// Where the camera is for the next steps: far regions (Settings::farDistance) lie far from it.
    void setViewpoint(glm::vec3 eye) { viewpoint_ = eye; }

    /// Splits the regions over the ranks of the run (ranges of consecutive regions holding about
    /// as many starting walkers each): this rank steps only its own, exchanging ghosts and handovers
    /// with the others each step, and rank 0 gathers the walkers' state (WalkerRecord), so that
    /// position(), speed(), region() and the Behaviour calls there are those of one process for
    /// every walker present() (all of them unless a gather view is set). Other ranks know only
    /// their own walkers. `ranks` must outlive the stepping. Throws
    /// std::logic_error after the first step; exchanges throw RankError (a rank failed).
    void distribute(Ranks& ranks);
    /// Distributed, on every rank before the first step: each rank poses the walkers it steps,
    /// rather than rank 0 posing every walker. Each step then needs a gather view (rank 0's
    /// setGatherView; a step without one throws std::logic_error), and on every rank the walkers
    /// present() are its own near the view; the others' near it are known(), for its own to look
    /// at (sent only when someone looks: a margin beyond the shown one). Throws std::logic_error
    /// after the first step or unless distributed.
    void setPosedWhereStepped(bool posed);
    /// Whether each rank poses the walkers it steps.
    bool posedWhereStepped() const { return posedWhereStepped_; }
    /// A byte kept with walker `slot` for the process that poses it (its LOD tiers): set there,
    /// it travels with the walker when a region of another rank takes it over.
    std::uint8_t carried(std::uint32_t slot) const;
    /// Sets walker `slot`'s carried byte (see carried()).
    void setCarried(std::uint32_t slot, std::uint8_t value);
    /// Whether distribute() was called.
    bool distributed() const { return ranks_ != nullptr; }
    /// Distributed, set on rank 0 before a step: the other ranks then send rank 0 only the walkers
    /// standing within `margin` metres of `view` (the frustum the frame will cull against, sent to
    /// them in the step), and the others, rank 0's own included, are not present() on rank 0 until
    /// they come near it again: what rank 0 holds depends on the view, not on who steps whom.
    /// The margin must cover how far a walker's Refpoint Bsphere reaches from where it stands, and
    /// how far away anyone who matters to a visible walker may be (whom it looks at). Without a view
    /// (the default) every walker is sent. Of those sent, the walkers standing farther than
    /// `shownMargin` outside the view (which must cover how far a Refpoint Bsphere reaches, with
    /// room to spare) cannot be seen: they are known() on rank 0, for those who can to look at, but
    /// not present(), so its cascade skips them unread. Throws std::invalid_argument for a margin
    /// that is negative or not finite, or a shown margin beyond the margin.
    void setGatherView(std::optional<Frustum> view, double margin = 0.0, double shownMargin = 0.0);
    /// Walkers rank 0 holds this step's state of: every one, unless a gather view left some out.
    std::size_t presentCount() const;
    /// Of those, walkers that may be seen (present()).
    std::size_t shownCount() const;
    /// Regions this rank steps, [first, second) (all of them unless distributed; valid after the
    /// first step).
    std::pair<std::uint32_t, std::uint32_t> ownRegions() const { return {firstRegion_, endRegion_}; }
    /// Each rank's share of the last step, indexed by rank: on rank 0 every rank's, elsewhere only
    /// this rank's entry is filled; empty unless distributed.
    std::span<const RankStepRecord> rankSteps() const;

    std::span<const double> levelEnds() const override { return levelEnds_; }
    void advance(const FrameContext& context) override;
    Mat4 referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) override;
    /// Every slot's at once: the same matrices, the headings' sines and cosines taken in pairs.
    void referencePoints(std::span<const std::uint32_t> slots, const FrameContext& context, OpTally* ops,
                         std::span<Mat4> out) override;
    RootPose skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) override;
    void pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
              std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) override;
    BoundingSphere skeletonRootExtent(std::uint32_t slot) const override;
    bool posesFromTemplateClips() const override { return true; }
    bool presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const override;
    bool known(std::uint32_t slot) const override;
    /// Each walker's region (as region()).
    bool steppingRegions(std::span<const std::uint32_t> slots, std::span<std::uint32_t> regions) const override;
    std::optional<std::span<const std::uint32_t>> presentSlots() const override;
    double poseMargin(std::uint32_t slot) const override;
    double clipTime(std::uint32_t slot, double time) const override;
    int mainClip(std::uint32_t slot) const override { return actors_[slot].walkClip; }
    std::size_t bytesPerSlot() const override;

private:
    // The extent and blend margin of one template's clips.
    struct ClipBounds {
        const ActorTemplate* tmpl;
        int walkClip, runClip;
        BoundingSphere extent;
        double blendMargin;
    };
    void start();
    void walk(std::uint32_t slot, double dt);
    // Distributed: lists the walkers of this rank's regions; sends and takes in the step's walkers.
    void listOwn();
    void gatherOwn(RankStepRecord& mine, const Stopwatch& watch);

    std::shared_ptr<const NavMesh> nav_;
    Settings settings_;
    std::vector<double> levelEnds_;
    EffectCounters* counters_;
    std::vector<Actor> actors_;
    std::vector<locomotion::WalkerState> state_;
    std::vector<std::uint32_t> regionOf_;  // per slot: the region owning it (apart: a frame reads it alone)
    std::vector<ClipBounds> clipBounds_;
    bool started_ = false;
    std::size_t lastGhosts_ = 0, lastHandovers_ = 0, lastDeferred_ = 0;
    double lastAdvanceMs_ = 0.0;
    glm::vec3 viewpoint_{0.0f};  // far regions lie far from it
    std::unique_ptr<locomotion::RegionStepper> regions_;  // from the first step
    // Distributed: the ranks, their exchanges (from the first step), the region range this rank
    // steps and the walkers of its regions.
    Ranks* ranks_ = nullptr;
    std::unique_ptr<locomotion::RankExchange> exchange_;
    std::optional<Frustum> gatherView_;
    double gatherMargin_ = 0.0, shownMargin_ = 0.0;
    std::uint32_t firstRegion_ = 0, endRegion_ = 0;
    std::vector<std::uint32_t> ownSlots_;
    bool posedWhereStepped_ = false;
};

}  // namespace throng::sim
