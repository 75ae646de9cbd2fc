#pragma once
// Gaze (seed 002 §5.3): a layer over any behaviour that turns an actor's neck and head towards
// someone nearby, within joint limits. Whom to look at is chosen once per frame for every actor
// (from positions and each actor's own random stream, so it is view-independent); the turn is
// applied when the actor is posed, with two precision levels: neck and head sharing the turn near,
// the neck alone farther, nothing beyond the last band (or once the neck is deactivated).
//
// The choice has no memory: in each of its periods an actor looks at whoever within range draws
// the lowest of its random numbers for that period. So it depends only on who is within range now
// and not on who was before, nor on the order neighbours are visited; a process that holds only
// the actors near the view (the others are not known()) chooses as one holding everyone does.

#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "throng/sim/BehaviourLayer.h"
#include "throng/sim/EffectCounters.h"

namespace throng::sim {

/// Head and neck look-at over a base behaviour.
class GazeLayer : public BehaviourLayer {
public:
    /// How people look.
    struct Settings {
        std::vector<double> levels{12.0, 40.0};  ///< gaze bands: neck and head, then neck only
        double range = 10.0;                    ///< how far someone is noticed, metres
        double maxYaw = 1.1;                    ///< radians left or right (neck and head together)
        double maxPitch = 0.45;                 ///< radians up or down
        double eyeHeight = 1.6;                 ///< where a looked-at person's face is, above the ground
        std::uint64_t seed = 1;                 ///< who catches whose eye, and when
    };

    /// A gaze layer over `base`, counting into `counters` (may be null).
    GazeLayer(std::shared_ptr<Behaviour> base, Settings settings, EffectCounters* counters = nullptr);

    /// Makes base slot `baseSlot` (an actor of template `tmpl`) gaze; returns the layer's slot
    /// (the same number). Actors of templates without a node named like "neck" do not turn.
    std::uint32_t wrap(std::uint32_t baseSlot, const std::shared_ptr<const ActorTemplate>& tmpl, std::uint64_t stream);
    /// The slot `slot` is looking at, or -1.
    int lookingAt(std::uint32_t slot) const { return state_[slot].target; }

    void advance(const FrameContext& context) override;
    void pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
              std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) override;
    double poseMargin(std::uint32_t slot) const override { return base_->poseMargin(slot) + state_[slot].margin; }
    std::size_t bytesPerSlot() const override { return base_->bytesPerSlot() + sizeof(State); }

private:
    struct Joints {
        int neck = -1, head = -1;
    };
    struct State {
        const ActorTemplate* tmpl = nullptr;
        Joints joints;
        std::uint64_t stream = 0;
        int target = -1;
        glm::dvec3 position{0.0};
        glm::dvec3 lookAt{0.0};
        double margin = 0.0;
    };
    Joints jointsOf(const ActorTemplate& tmpl);
    void turn(const ActorTemplate& tmpl, int node, const glm::dquat& rotation, std::span<float> dofs,
              std::span<const std::uint8_t> active, OpTally* ops) const;

    Settings settings_;
    EffectCounters* counters_;
    std::vector<int> gazeLevel_;      // per merged level: the gaze's level
    std::vector<State> state_;
    std::map<const ActorTemplate*, Joints> joints_;
    std::vector<std::uint32_t> cellStart_, cellFill_, cellActors_;  // neighbour grid, reused
    std::vector<glm::dvec2> cellPositions_;  // the grid's actors' positions (x, z), beside cellActors_
    std::vector<std::uint8_t> present_;  // per slot: a gazing actor whose state is this step's
};

}  // namespace throng::sim
