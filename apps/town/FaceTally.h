#pragma once
// The face layers' work of each frame: how many expressions, blinks and phrases were evaluated, and
// the layers' time, since the last count. Rank 0 counts its own; ranks posing their own walkers
// count theirs and send them with their share of the frame.

#include <cstdint>

#include "throng/sim/Simulation.h"

namespace throng::town {

/// The face layers' evaluations and seconds since the last take().
class FaceTally {
public:
    /// What one frame evaluated.
    struct Counts {
        std::uint64_t evaluations[3] = {0, 0, 0};  ///< expressions, blinks, phrases
        double seconds = 0.0;                      ///< the layers' time (all threads)
    };
    /// The counts since the last call (since the world was built, the first time).
    Counts take(const sim::Simulation& world) {
        Counts c;
        double seconds = 0.0;
        for (const auto& layer : world.faceLayers()) seconds += layer->flushCounts();
        const char* effects[3] = {"face", "blink", "phrase"};
        for (int k = 0; k < 3; ++k) {
            const std::uint64_t ticks = world.effects().of(effects[k]).ticks;
            c.evaluations[k] = ticks - ticksSeen_[k];
            ticksSeen_[k] = ticks;
        }
        c.seconds = seconds - secondsSeen_;
        secondsSeen_ = seconds;
        return c;
    }

private:
    std::uint64_t ticksSeen_[3] = {0, 0, 0};
    double secondsSeen_ = 0.0;
};

}  // namespace throng::town
