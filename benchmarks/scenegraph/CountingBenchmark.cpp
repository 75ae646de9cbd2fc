// What FMULT counting costs: one traditional frame (APP, matrices and bounds recomputed in full,
// CULL) of a 2000-figure field with counting switched off and on at run time. The same source is
// also built with counting compiled out (bench_counting_compiled_out); counting_overhead.py runs
// both and prints the three side by side.

#include <benchmark/benchmark.h>

#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/TraditionalProcessor.h"
#include "throng/testkit/FigureField.h"

using namespace throng;

namespace {

void runFrames(benchmark::State& state, bool counting) {
    const int figures = static_cast<int>(state.range(0));
    auto scene = testkit::buildFigureField(figures);
    const double extent = testkit::figureFieldExtent(figures);
    Camera camera;
    camera.setPerspective(1.0, 16.0 / 9.0, 0.1, 3000.0);
    camera.setLookAt(Vec3(extent / 2, 30, extent * 1.2), Vec3(extent / 2, 0, extent / 2));
    TraditionalProcessor processor;
    processor.setFullRecompute(true);
    processor.counter().setEnabled(counting);
    double t = 0.0;
    for (auto _ : state) {
        processor.processFrame(*scene, camera, t);
        t += 1.0 / 60.0;
    }
    state.counters["compiled_in"] = OpCounter::compiledIn() ? 1 : 0;
    state.counters["fmult_per_frame"] = static_cast<double>(processor.statistics().fmultTotal);
    state.counters["frames_per_s"] = benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_TraditionalFrame_CountingOff(benchmark::State& state) { runFrames(state, false); }
void BM_TraditionalFrame_CountingOn(benchmark::State& state) { runFrames(state, true); }
BENCHMARK(BM_TraditionalFrame_CountingOff)->Arg(2000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TraditionalFrame_CountingOn)->Arg(2000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
