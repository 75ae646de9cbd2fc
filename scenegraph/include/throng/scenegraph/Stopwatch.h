#pragma once
// Wall-clock timing of frame phases.

#include <chrono>

namespace throng {

/// Measures elapsed wall-clock time from construction or the last restart().
class Stopwatch {
public:
    Stopwatch() : start_(Clock::now()) {}
    /// Restarts the measurement.
    void restart() { start_ = Clock::now(); }
    /// Milliseconds since the start.
    double elapsedMs() const {
        return std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
    }

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_;
};

}  // namespace throng
