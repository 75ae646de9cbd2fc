// Traditional against actor processing (seed 002 §4.2): wall-clock APP+CULL time of the same frame
// of the same scene, for 100 to 100,000 actors, with Table 2's proportions (the cost model's
// example scene scaled up) and with a town-like spread. Each iteration runs one frame of each
// method back to back, so noise touches both alike; the counters give their times and the ratio.

#include <benchmark/benchmark.h>

#include <memory>

#include "throng/actors/ActorProcessor.h"
#include "throng/actors/CostModelScene.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/Table3Template.h"
#include "throng/scenes/TownSpread.h"

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
    CostModelSceneOptions options;
    options.counts = CascadeCounts::scaled(actors);
    options.group = true;
    CostModelScene built = buildCostModelScene(*s.crowd, makeTable3Template(), std::make_shared<KeyframeBehaviour>(), options);
    s.root = built.root;
    s.camera = built.camera;
    s.time = built.time;
    return s;
}

Scene townScene(std::size_t actors) {
    Scene s;
    scenes::TownSpread town = scenes::buildTownSpread(*s.crowd, actors, 40.0 * std::sqrt(double(actors)));
    s.root = town.root;
    s.camera = town.camera;
    return s;
}

void compare(benchmark::State& state, Scene scene) {
    ActorProcessor processor(*scene.crowd);
    double traditionalMs = 0.0, actorMs = 0.0, visible = 0.0;
    std::int64_t frames = 0;
    // One untimed frame of each: first-touch allocations are not what is compared.
    processor.setProcessing(Processing::Traditional);
    processor.processFrame(*scene.root, scene.camera, scene.time);
    processor.setProcessing(Processing::Actor);
    processor.processFrame(*scene.root, scene.camera, scene.time);
    for (auto _ : state) {
        const double t = scene.time + double(frames % 2) * 1e-9;  // Table 2 holds at its own time
        processor.setProcessing(Processing::Traditional);
        traditionalMs += processor.processFrame(*scene.root, scene.camera, t).appCullMs();
        processor.setProcessing(Processing::Actor);
        const ActorFrameStatistics& s = processor.processFrame(*scene.root, scene.camera, t);
        actorMs += s.appCullMs();
        visible += double(s.actorsPosed);
        ++frames;
    }
    state.counters["actors"] = double(scene.crowd->size());
    state.counters["posed"] = visible / double(frames);
    state.counters["traditional_ms"] = traditionalMs / double(frames);
    state.counters["actor_ms"] = actorMs / double(frames);
    state.counters["speedup"] = traditionalMs / actorMs;
}

void BM_Table2Proportions(benchmark::State& state) { compare(state, table2Scene(std::size_t(state.range(0)))); }
void BM_TownSpread(benchmark::State& state) { compare(state, townScene(std::size_t(state.range(0)))); }

BENCHMARK(BM_Table2Proportions)->Arg(100)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK(BM_TownSpread)->Arg(100)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->MinTime(0.5);

}  // namespace

BENCHMARK_MAIN();
