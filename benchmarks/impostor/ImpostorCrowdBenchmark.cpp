// Impostor crowds (DESIGN.md, Impostors): the morph work of a frame depends on the views x key-
// frames in use, not on the number of actors, because the MorphCache makes each needed cell once.
//
// ImpostorCrowd/N: N seed humanoids (1k, 4k, 16k) all beyond the impostor distance, random
// headings and clip phases, in front of the camera. Each frame: actor processing (impostors: no
// Skeleton node processed), then ImpostorBatcher builds the quad instances and morphs the dropped
// cells the frame needs on the GPU (llvmpipe here; cache capacity 0, so every frame morphs all it
// needs again: the worst case). Counters: cells morphed per frame, morph+batch ms per frame,
// processing ms, impostors.
//
// HybridScene/10000: 10k actors from 5 m to 300 m; near ones are geometry, far ones impostors
// (distance 60 m, hysteresis 5 m), drawn at 640x360 by CrowdRenderer (meshes, then impostor quads). Counters: impostors, actors posed, Skeleton nodes evaluated, cells morphed, and the
// times of processing, batching (with morphing) and drawing per frame.

#include <benchmark/benchmark.h>

#include <memory>
#include <random>

#include "throng/bench/MeanCounters.h"
#include "throng/actors/Actor.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/render/GpuMorpher.h"
#include "throng/render/ImpostorBaker.h"
#include "throng/render/ImpostorBatcher.h"
#include "throng/render/ImpostorDrawable.h"
#include "throng/render/ImpostorRenderer.h"
#include "throng/render/GlRenderer.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"

using namespace throng;

namespace {

// The baked humanoid, shared by every benchmark of the run.
struct Baked {
    std::shared_ptr<GlContext> context;
    std::shared_ptr<const ActorTemplate> tmpl;
    std::shared_ptr<const ImpostorAtlas> atlas;
    std::shared_ptr<const ImpostorDrawable> drawable;
    std::unique_ptr<GpuMorpher> gpu;

    Baked() {
        context = createContext(ContextOptions{64, 64, false});
        tmpl = makeSeedHumanoid();
        ImpostorBakeOptions o;
        o.cellSize = 64;
        ImpostorBaker baker(context, tmpl, tmpl->findClip("walk"), o);
        auto a = std::make_shared<ImpostorAtlas>(baker.bake());
        a->dropOddKeyframes();
        atlas = a;
        drawable = std::make_shared<ImpostorDrawable>(atlas);
        gpu = std::make_unique<GpuMorpher>(context);
    }
    static Baked& get() {
        static Baked b;
        return b;
    }
};

struct Scene {
    std::unique_ptr<Crowd> crowd = std::make_unique<Crowd>();
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::vector<double> timeOffset;  // per actor
    Camera camera;
};

// `n` actors scattered over x in [-w, w], z in [zNear, zFar] (negative: in front of the camera).
Scene makeScene(std::size_t n, double w, double zNear, double zFar) {
    Baked& b = Baked::get();
    Scene s;
    auto behaviour = std::make_shared<KeyframeBehaviour>();
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> ux(-w, w), uz(zFar, zNear), uh(0.0, 6.283185307179586), ut(0.0, 2.0);
    for (std::size_t i = 0; i < n; ++i) {
        KeyframeBehaviour::Actor a;
        a.tmpl = b.tmpl;
        a.clip = b.tmpl->findClip("walk");
        a.position = Vec3(ux(rng), 0.0, uz(rng));
        a.heading = uh(rng);
        a.timeOffset = ut(rng);
        s.timeOffset.push_back(a.timeOffset);
        const ActorId id = s.crowd->add(b.tmpl, behaviour, behaviour->addActor(a));
        s.root->addChild(s.crowd->makeActorNode(id));
    }
    s.camera.setPerspective(1.0, 16.0 / 9.0, 0.5, 2000.0);
    s.camera.setLookAt(Vec3(0, 25, 0), Vec3(0, 0, -200));
    return s;
}

// What both benchmarks run: a processor showing the baked humanoid beyond `distance`, and the
// morph cache (8 features) and batcher that turn its impostor items into quads.
struct ImpostorPipeline {
    ActorProcessor processor;
    MorphCache cache;
    ImpostorBatcher batcher;

    ImpostorPipeline(const Scene& s, double distance, double hysteresis)
        : processor(*s.crowd), cache(options(), Baked::get().gpu.get()), batcher(cache) {
        processor.setImpostorDistance(distance, hysteresis);
        processor.setImpostor(*Baked::get().tmpl, Baked::get().drawable);
    }
    static MorphCacheOptions options() {
        MorphCacheOptions o;
        o.features = 8;
        return o;
    }
};

void ImpostorCrowd(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    Scene s = makeScene(n, 250.0, -80.0, -900.0);
    ImpostorPipeline p(s, 40.0, 2.0);
    auto& [processor, cache, batcher] = p;
    double t = 0.0, morphMs = 0.0, processMs = 0.0, morphed = 0.0, impostors = 0.0, requests = 0.0;
    std::int64_t frames = 0;
    for (auto _ : state) {
        processMs += processor.processFrame(*s.root, s.camera, t).appCullMs();
        batcher.build(processor.drawList(), s.camera);
        morphMs += batcher.statistics().ms;
        morphed += static_cast<double>(cache.statistics().synthesized);
        requests += static_cast<double>(cache.statistics().requests);
        impostors += static_cast<double>(batcher.statistics().impostors);
        t += 1.0 / 30.0;
        ++frames;
    }
    bench::setMeanCounters(state, double(frames), {{"impostors", impostors}, {"cellRequests", requests}, {"cellsMorphed", morphed},
                                                   {"morphMs", morphMs}, {"processMs", processMs}});
}
BENCHMARK(ImpostorCrowd)->Arg(1000)->Arg(4000)->Arg(16000)->Iterations(6)->Unit(benchmark::kMillisecond);

void HybridScene(benchmark::State& state) {
    Baked& b = Baked::get();
    const auto n = static_cast<std::size_t>(state.range(0));
    Scene s = makeScene(n, 150.0, -5.0, -300.0);
    ImpostorPipeline p(s, 60.0, 5.0);
    ActorProcessor& processor = p.processor;
    CrowdRendererOptions ro;
    ro.meshes.width = 640, ro.meshes.height = 360;
    ro.morph = ImpostorPipeline::options();
    CrowdRenderer renderer(b.context, ro);
    double t = 0.0, impostors = 0.0, posed = 0.0, nodes = 0.0, morphed = 0.0, processMs = 0.0, batchMs = 0.0,
           drawMs = 0.0;
    std::int64_t frames = 0;
    for (auto _ : state) {
        const ActorFrameStatistics& st = processor.processFrame(*s.root, s.camera, t);
        processMs += st.appCullMs();
        Stopwatch watch;
        renderer.drawFrame(s.camera, processor.drawList());
        drawMs += watch.elapsedMs();
        batchMs += renderer.statistics().impostorBatchMs;
        impostors += static_cast<double>(st.impostors);
        posed += static_cast<double>(st.actorsPosed);
        nodes += static_cast<double>(st.skeletonNodesEvaluated);
        morphed += static_cast<double>(renderer.statistics().cellsMorphed);
        t += 1.0 / 30.0;
        ++frames;
    }
    bench::setMeanCounters(state, double(frames), {{"impostors", impostors}, {"actorsPosed", posed}, {"skeletonNodes", nodes},
                                                   {"cellsMorphed", morphed}, {"processMs", processMs}, {"batchMorphMs", batchMs},
                                                   {"drawMs", drawMs}});
}
BENCHMARK(HybridScene)->Arg(10000)->Iterations(4)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
