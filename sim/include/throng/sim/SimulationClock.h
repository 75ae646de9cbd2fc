#pragma once
// Fixed-step simulation time. Time is computed from the step count, never accumulated, so a
// million steps land exactly where they should.

#include <cstdint>

#include "throng/scenegraph/FrameContext.h"

namespace throng::sim {

/// Counts fixed steps of `step` seconds.
class SimulationClock {
public:
    /// A clock with steps of `step` seconds (finite, > 0; default 1/60 s).
    explicit SimulationClock(double step = 1.0 / 60.0);
    /// The step, seconds.
    double step() const { return step_; }
    /// Steps taken so far.
    std::uint64_t frame() const { return frame_; }
    /// Simulation time of the current frame: frame() * step().
    double time() const { return static_cast<double>(frame_) * step_; }
    /// The current frame's context (time, step, frame number); `counter` is left null.
    FrameContext context() const { return FrameContext{time(), frame_ == 0 ? 0.0 : step_, frame_, nullptr}; }
    /// Moves to the next step.
    void advance() { ++frame_; }

private:
    double step_;
    std::uint64_t frame_ = 0;
};

}  // namespace throng::sim
