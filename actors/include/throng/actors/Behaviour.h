#pragma once
// What drives actors (seed 002 §4.2, §5.3): the Reference Point (simulation state, computed for every
// actor every frame whatever the camera), the Skeleton Root relative to it, and the DOF values of
// the active Skeleton nodes. A behaviour declares distance-banded levels: lower levels are cheaper
// and less precise; beyond the last band the actor keeps its rest pose. One behaviour object serves
// many actors, each with its own slot of state. referencePoint, skeletonRoot and pose may be called
// for different slots from several threads at once: they must touch only their slot's state.

#include <cstdint>
#include <optional>
#include <span>

#include "throng/actors/RootPose.h"
#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/FrameContext.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

class ActorTemplate;

/// Drives the actors registered with it (each identified by a slot the behaviour gave out).
class Behaviour {
public:
    virtual ~Behaviour() = default;

    /// Ends of the distance bands (scaled eye distance, increasing): level i runs while the
    /// distance is below levelEnds()[i]. Level 0 is the most precise.
    virtual std::span<const double> levelEnds() const = 0;

    /// The simulation step (Crowd::step), once per frame before any referencePoint() of that
    /// frame: advances state the behaviour's actors share (a navigation crowd, a flock) to
    /// `context.time`. Per-actor work inside may run in parallel with forEachChunk. Default: nothing.
    virtual void advance(const FrameContext& context) { (void)context; }
    /// Phase 1: the actor's Reference Point in its parent's frame for the frame `context`.
    /// Called exactly once per frame for every actor, before anything depends on the camera.
    virtual Mat4 referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) = 0;
    /// Phase 1 for several actors: out[k] = referencePoint(slots[k], context, ops), the same bits,
    /// for every k < slots.size() (`out` holds at least as many). Behaviours whose Reference Points
    /// share work (a batch of sines) override it. Default: one referencePoint call each.
    virtual void referencePoints(std::span<const std::uint32_t> slots, const FrameContext& context, OpTally* ops,
                                 std::span<Mat4> out) {
        for (std::size_t k = 0; k < slots.size(); ++k) out[k] = referencePoint(slots[k], context, ops);
    }
    /// Phase 3: the Skeleton Root relative to the Reference Point at `time`, at `level`.
    virtual RootPose skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) = 0;
    /// Phase 5: writes the DOF values of the nodes flagged in `active` (every node when empty) at
    /// `time` and `level` into `dofs` (the template's layout). Must not touch other nodes' values.
    virtual void pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
                      std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) = 0;

    /// Sphere (Reference Point frame) holding every place the Skeleton Root can take.
    virtual BoundingSphere skeletonRootExtent(std::uint32_t slot) const = 0;
    /// Whether poses come only from the template's clips, so the sampled Sklsroot radius bounds
    /// them; otherwise the actor uses the template's reach radius.
    virtual bool posesFromTemplateClips() const = 0;
    /// Metres the behaviour's poses may reach beyond those of the template's clips (blends of
    /// clips, layers turning a head): added to the Sklsroot radius of its actors. Default 0.
    virtual double poseMargin(std::uint32_t slot) const { (void)slot; return 0.0; }
    /// The main clip of actor `slot` (the one impostors are baked from: the walk clip of a walker),
    /// or -1 when it plays none. Default -1.
    virtual int mainClip(std::uint32_t slot) const { (void)slot; return -1; }
    /// Time into its main clip (the one impostors are baked from: the walk clip of a walker) that
    /// actor `slot` shows at `time`. Default: `time` itself.
    virtual double clipTime(std::uint32_t slot, double time) const { (void)slot; return time; }

    /// Which of `slots` have in this process the state of the last step. An actor is absent only
    /// when another process of the run simulates it and did not send it this step, because it
    /// cannot be seen (nor be looked at by anyone who can): phase 1 skips it and CULL 1 rejects it
    /// unread, so what this process spends on it does not grow with the actors it does not show.
    /// Returns true when every one is present (`present` is then left as it is); otherwise writes
    /// present[k] (1 or 0) for every k < slots.size(). One call serves many actors. Default: true.
    virtual bool presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const {
        (void)slots, (void)present;
        return true;
    }
    /// The slots present this step (those presence() would call present), in increasing order,
    /// when this behaviour knows them as a list and most of its actors are absent (the walkers near
    /// the view, on the rank of a distributed run that draws); std::nullopt (the default) when every
    /// actor must be asked. A crowd one of whose behaviours lists its slots visits only the listed
    /// actors, those of the behaviours that list none, and those it showed last frame: phase 1 and
    /// placement then cost what the process shows, not what it holds.
    virtual std::optional<std::span<const std::uint32_t>> presentSlots() const { return std::nullopt; }
    /// Whether this process holds actor `slot`'s state of the last step, absent or not: an absent
    /// actor that someone present may look at is known. Default true.
    virtual bool known(std::uint32_t slot) const { (void)slot; return true; }
    /// The part of the world that steps each of `slots` (a walker's region), written to
    /// regions[k]: actors of different parts are never binned together (occlusion's cells), so that
    /// a process holding some of the parts bins its actors as one process holding all of them would.
    /// Returns false when this behaviour divides nothing (`regions` is then left as it is). One call
    /// serves many actors. Default false.
    virtual bool steppingRegions(std::span<const std::uint32_t> slots, std::span<std::uint32_t> regions) const {
        (void)slots, (void)regions;
        return false;
    }
    /// Whether actor `slot` is present (see presence()).
    bool present(std::uint32_t slot) const {
        std::uint8_t here = 1;
        return presence({&slot, 1}, {&here, 1}) || here != 0;
    }

    /// Bytes of state one more actor takes in this behaviour.
    virtual std::size_t bytesPerSlot() const = 0;

    /// Level for a scaled eye distance: the first band holding it, or levelEnds().size() (off).
    int levelFor(double distance) const {
        const auto ends = levelEnds();
        for (std::size_t i = 0; i < ends.size(); ++i)
            if (distance < ends[i]) return static_cast<int>(i);
        return static_cast<int>(ends.size());
    }
};

}  // namespace throng
