// Traditional against actor processing (seed 002 §4.2): wall-clock APP+CULL time of the same frame
// of the same scene, with Table 2's proportions (the cost model's example scene scaled up) and with
// a town-like spread, from 1,000 to 1,000,000 actors. Each iteration runs one frame of each method
// back to back on the same state, so noise touches both alike; the counters give their times, the
// ratio, the cost per posed actor and the pipeline's FMULT rate relative to a fixed scalar kernel
// timed in every iteration (so a figure can be compared across machines and commits:
// benchmarks/check-baseline does). At 1M Table-2 actors traditional processing would need more
// memory than a 24 GB machine has, so that size runs actor processing alone.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "throng/actors/ActorProcessor.h"
#include "throng/research/CostModelScene.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/Table3Template.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/scenegraph/Transform.h"
#include "throng/testkit/TownSpread.h"

using namespace throng;

namespace {

struct Scene {
    std::unique_ptr<Crowd> crowd = std::make_unique<Crowd>();
    std::shared_ptr<Group> root;
    Camera camera;
    double time = 0.0;
};

Scene table2Scene(std::size_t actors) {
    Scene s;
    CostModelScene built = buildTable2Scene(*s.crowd, actors);
    s.root = built.root;
    s.camera = built.camera;
    s.time = built.time;
    return s;
}

Scene townScene(std::size_t actors) {
    Scene s;
    testkit::TownSpread town = testkit::buildTownSpread(*s.crowd, actors, 40.0 * std::sqrt(double(actors)));
    s.root = town.root;
    s.camera = town.camera;
    return s;
}

// Frames of each method run before timing: both draw lists of the double buffer grown and their
// storage merged into one block, so timed frames neither allocate nor fault (see FrameArena).
constexpr int kWarmupFrames = 4;

// A fixed scalar kernel, the yardstick of the machine's arithmetic speed: double affine products over
// a small set of matrices (in cache). Timed inside every iteration, beside the frames, so that a
// slower or faster spell of a shared machine touches both alike.
class Yardstick {
public:
    Yardstick() : m_(64, Mat4(1.0)) {
        for (std::size_t i = 0; i < m_.size(); ++i) {  // small turns about +Y and moves: the products stay finite
            const double a = 0.01 * double(i);
            m_[i][0] = Vec4(std::cos(a), 0.0, -std::sin(a), 0.0);
            m_[i][2] = Vec4(std::sin(a), 0.0, std::cos(a), 0.0);
            m_[i][3] = Vec4(0.001 * double(i), 0.0, -0.002, 1.0);
        }
        OpTally tally;
        composeAffine(m_[0], m_[1], &tally);
        perProduct_ = double(tally.fmult());
    }
    // Runs the kernel once (a fixed number of products) and adds its FMULT and microseconds.
    void run() {
        constexpr int kProducts = 20000;
        Mat4 acc(1.0);
        Stopwatch watch;
        for (int k = 0; k < kProducts; ++k) acc = composeAffine(m_[static_cast<std::size_t>(k) & 63], acc);
        us_ += watch.elapsedMs() * 1000.0;
        benchmark::DoNotOptimize(acc);
        fmult_ += perProduct_ * kProducts;
    }
    // FMULT per microsecond over every run.
    double rate() const { return fmult_ / us_; }

private:
    std::vector<Mat4> m_;
    double perProduct_ = 0.0, fmult_ = 0.0, us_ = 0.0;
};

// FMULT one frame of the current method does (counted in an untimed frame at the same time: the
// count does not depend on the frame).
double countedFmult(ActorProcessor& processor, Scene& scene) {
    processor.counter().setEnabled(true);
    const double fmult = double(processor.processFrame(*scene.root, scene.camera, scene.time).fmultTotal);
    processor.counter().setEnabled(false);
    return fmult;
}

void compare(benchmark::State& state, Scene scene, bool withTraditional) {
    ActorProcessor processor(*scene.crowd);
    Yardstick yardstick;
    processor.setProcessing(Processing::Actor);
    const double actorFmult = countedFmult(processor, scene);
    double traditionalFmult = 0.0;
    if (withTraditional) {
        processor.setProcessing(Processing::Traditional);
        traditionalFmult = countedFmult(processor, scene);
    }
    for (int k = 0; k < kWarmupFrames; ++k)
        for (const Processing p : {Processing::Traditional, Processing::Actor}) {
            if (p == Processing::Traditional && !withTraditional) continue;
            processor.setProcessing(p);
            processor.processFrame(*scene.root, scene.camera, scene.time + double(k % 2) * 1e-9);
        }
    double traditionalMs = 0.0, actorMs = 0.0, posed = 0.0, items = 0.0;
    double phase[7] = {};
    std::int64_t frames = 0;
    for (auto _ : state) {
        const double t = scene.time + double(frames % 2) * 1e-9;  // Table 2 holds at its own time
        if (withTraditional) {
            processor.setProcessing(Processing::Traditional);
            traditionalMs += processor.processFrame(*scene.root, scene.camera, t).appCullMs();
        }
        processor.setProcessing(Processing::Actor);
        const ActorFrameStatistics& s = processor.processFrame(*scene.root, scene.camera, t);
        yardstick.run();
        actorMs += s.appCullMs();
        posed += double(s.actorsPosed);
        items += double(s.drawItems);
        const double phases[7] = {s.refpointMs + s.matricesBoundsMs, s.cullMs, s.skeletonRootMs, s.cull2Ms, s.poseMs, s.cull3Ms,
                                  s.drawListMs};
        for (int k = 0; k < 7; ++k) phase[k] += phases[k];
        ++frames;
    }
    const double n = double(frames);
    state.counters["actors"] = double(scene.crowd->size());
    state.counters["posed"] = posed / n;
    state.counters["draw_items"] = items / n;
    state.counters["actor_ms"] = actorMs / n;
    // Per actor posed (what grows with the visible crowd) and per actor in the scene (what every
    // actor costs, seen or not: its Reference Point).
    state.counters["actor_us_per_posed"] = posed > 0 ? 1000.0 * actorMs / posed : 0.0;
    state.counters["actor_ns_per_actor"] = 1e6 * actorMs / n / double(scene.crowd->size());
    // The pipeline's arithmetic rate over the yardstick's (1 = as fast per FMULT as the scalar kernel).
    state.counters["actor_fmult_rate"] = actorFmult / (1000.0 * actorMs / n) / yardstick.rate();
    const char* names[7] = {"refpoint_ms", "cull1_ms", "sklsroot_ms", "cull2_ms", "pose_ms", "cull3_ms", "drawlist_ms"};
    for (int k = 0; k < 7; ++k) state.counters[names[k]] = phase[k] / n;
    if (withTraditional) {
        state.counters["traditional_ms"] = traditionalMs / n;
        state.counters["speedup"] = traditionalMs / actorMs;
        state.counters["traditional_fmult_rate"] = traditionalFmult / (1000.0 * traditionalMs / n) / yardstick.rate();
    }
}

void BM_Table2Proportions(benchmark::State& state) {
    const auto actors = std::size_t(state.range(0));
    compare(state, table2Scene(actors), actors <= 100000);
}
void BM_TownSpread(benchmark::State& state) { compare(state, townScene(std::size_t(state.range(0))), true); }

// Enough frames for a steady mean at every size, in a few seconds each.
BENCHMARK(BM_Table2Proportions)->Unit(benchmark::kMillisecond)->Arg(1000)->MinTime(1.0);
BENCHMARK(BM_Table2Proportions)->Unit(benchmark::kMillisecond)->Arg(10000)->MinTime(3.0);
BENCHMARK(BM_Table2Proportions)->Unit(benchmark::kMillisecond)->Arg(100000)->Iterations(10);
BENCHMARK(BM_Table2Proportions)->Unit(benchmark::kMillisecond)->Arg(1000000)->Iterations(6);
BENCHMARK(BM_TownSpread)->Unit(benchmark::kMillisecond)->Arg(1000)->MinTime(1.0);
BENCHMARK(BM_TownSpread)->Unit(benchmark::kMillisecond)->Arg(10000)->MinTime(3.0);
BENCHMARK(BM_TownSpread)->Unit(benchmark::kMillisecond)->Arg(100000)->Iterations(10);
BENCHMARK(BM_TownSpread)->Unit(benchmark::kMillisecond)->Arg(1000000)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
