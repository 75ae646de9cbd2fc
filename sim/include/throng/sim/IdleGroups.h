#pragma once
// People standing in small groups, facing each other (a key-framed idle clip, or the walk clip
// held). With the gaze effect declared, they look at one another in turn.

#include "throng/actors/KeyframeBehaviour.h"
#include "throng/sim/EffectCounters.h"

namespace throng::sim {

/// Standing groups: key-frame playback with fixed Reference Points, counted as the "idle" effect.
class IdleGroups : public KeyframeBehaviour {
public:
    /// Idle groups with the given level bands, counting into `counters` (may be null).
    explicit IdleGroups(std::vector<double> levelEnds = {60.0, std::numeric_limits<double>::infinity()},
                        EffectCounters* counters = nullptr)
        : KeyframeBehaviour(std::move(levelEnds)), counters_(counters) {
        if (counters_) counters_->constructed("idle");
    }
    /// Counts one tick per person per frame.
    void advance(const FrameContext&) override {
        if (counters_) counters_->ticked("idle", people_);
    }
    /// Adds a person (see KeyframeBehaviour::addActor).
    std::uint32_t addPerson(const Actor& actor) {
        ++people_;
        return addActor(actor);
    }

private:
    EffectCounters* counters_;
    std::uint64_t people_ = 0;
};

}  // namespace throng::sim
