#pragma once
// Google Benchmark counters as means per frame: the suites sum their figures over the iterations
// and report each divided by the frames, named as their tables and scripts read them.

#include <initializer_list>
#include <utility>

#include <benchmark/benchmark.h>

namespace throng::bench {

/// Sets each counter `name` of `state` to `sum / frames` (0 frames: the sums as they are).
inline void setMeanCounters(benchmark::State& state, double frames, std::initializer_list<std::pair<const char*, double>> sums) {
    const double n = frames > 0 ? frames : 1.0;
    for (const auto& [name, sum] : sums) state.counters[name] = sum / n;
}

}  // namespace throng::bench
