// DRAW of a walking CesiumMan crowd at middle distance (20 to 40 m from the camera), 1280x720
// headless (OSMesa, llvmpipe), skinned and from the key-pose cache side by side (seed 004 §5):
//
//   BM_KeyPoseDraw/mode:0/instances:N   skinned: every actor's palette at its own clip time, GPU
//                                       linear-blend skinning in the vertex shader
//   BM_KeyPoseDraw/mode:1/instances:N   intermittent key-pose cache: every actor shows its nearest
//                                       key-pose (KeyPoseCache, 15 key-poses per second, 64 rows)
//   BM_KeyPoseDraw/mode:2/instances:N   interpolative: the two key-poses around its clip time, blended
//   BM_KeyPoseDraw/mode:3/instances:N   intermittent without retention: the renderer's rows are
//                                       freed before each frame, so every pose shown is skinned again
//                                       (what the cache saves by keeping rows across frames)
//   BM_KeyPoseDraw/mode:4/instances:N   rigid: the same mesh in its bind pose, no skinning and no
//                                       cache (the floor: what drawing the triangles costs alone)
//
// Each timed iteration is one frame: beginFrame, draw of the whole list (palette upload or row
// fills included), endFrame (OsMesaContext::present: glFinish, so rasterisation is timed too). The
// actors' poses advance 1/30 s per frame; the draw lists of a cycle of frames are built before
// timing (APP and CULL are not DRAW). At the end the program prints, per case, the median and the
// fastest frame by wall time, by CPU time of every thread (the drawing thread's vertex work and
// llvmpipe's rasteriser threads: on a machine shared with other work, the steadier figure) and by
// the drawing thread's CPU time alone, and the ratios skinned / case.
// Run from the dev or release build, the repetitions interleaved with other work on the machine:
//   ./build/dev/benchmarks/render/bench_keypose_draw --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
// With THRONG_BENCH_FRAMES=<folder>, each case writes its first frame there as PNG.

#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "throng/testkit/Assets.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/ImageIO.h"
#include "throng/render/OsMesaContext.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng {
namespace {

constexpr int kWidth = 1280, kHeight = 720;
constexpr int kCycle = 8;            // frames whose lists are built before timing, drawn in turn
constexpr double kFrameStep = 1.0 / 30.0;
const char* const kModeNames[] = {"skinned", "intermittent", "interpolative", "intermittent-no-retention", "rigid"};

struct CesiumMan {
    std::shared_ptr<const ActorTemplate> tmpl;
    std::shared_ptr<const MeshDrawable> drawable;
    std::uint32_t skin = 0;
};

const CesiumMan& cesiumMan() {
    static const CesiumMan c = [] {
        const std::string path = testkit::sharedAssets() + "/characters/CesiumMan.glb";
        static const CharacterAsset asset = loadCharacter(path);
        CesiumMan m;
        m.tmpl = asset.primaryTemplate();
        if (!m.tmpl || m.tmpl->clips().empty()) throw std::runtime_error(path + ": no animated character");
        for (const VaLodLevel& level : m.tmpl->rootGeometry().levels())
            if (level.skin >= 0)
                if (auto d = std::dynamic_pointer_cast<const MeshDrawable>(level.drawable)) {
                    m.drawable = d;
                    m.skin = static_cast<std::uint32_t>(level.skin);
                    break;
                }
        if (!m.drawable) throw std::runtime_error(path + ": no skinned mesh");
        return m;
    }();
    return c;
}

// N actors scattered 20 to 40 m in front of the camera, inside its view, each with its own heading
// and walk phase; the draw lists of kCycle frames.
struct Crowd {
    Camera camera;
    std::vector<Mat4> worlds;
    std::vector<double> phases;
    std::unique_ptr<KeyPoseCache> cache;
    DrawList lists[kCycle];
    std::uint64_t fillsPerCycle = 0;  // row updates KeyPoseRows asked for (warm-up cycle excluded)

    Crowd(int n, int mode) {
        const CesiumMan& c = cesiumMan();
        camera.setPerspective(std::numbers::pi / 4.0, double(kWidth) / kHeight, 0.5, 200.0);
        camera.setLookAt(Vec3(0.0, 8.0, 0.0), Vec3(0.0, 0.0, -30.0));  // a raised view, as over a town
        std::mt19937 rng(20100412u);  // fixed: every mode draws the same crowd
        std::uniform_real_distribution<double> u(0.0, 1.0);
        const double halfWidth = std::tan(0.5 * camera.fovY()) * double(kWidth) / kHeight * 0.9;  // of the view at depth 1
        for (int i = 0; i < n; ++i) {
            const double z = 20.0 + 20.0 * u(rng), x = (2.0 * u(rng) - 1.0) * halfWidth * z;
            worlds.push_back(glm::rotate(glm::translate(Mat4(1.0), Vec3(x, 0.0, -z)), 2.0 * std::numbers::pi * u(rng),
                                         Vec3(0.0, 1.0, 0.0)));
            phases.push_back(10.0 * u(rng));
        }
        const ActorTemplate& t = *c.tmpl;
        const AnimationClip& clip = *t.clips()[0];
        if (mode >= 1 && mode <= 3) {
            KeyPoseCacheSettings settings;
            settings.rows = 64;
            settings.mode = mode == 2 ? KeyPoseMode::Interpolative : KeyPoseMode::Intermittent;
            cache = std::make_unique<KeyPoseCache>(c.tmpl, settings);
        }
        std::vector<float> dofs(t.dofValueCount());
        std::vector<Affine> model(t.nodeCount());
        std::vector<glm::mat4> palette(t.skins()[c.skin].joints.size());
        std::vector<KeyPoseSample> samples(std::size_t(n), KeyPoseSample{});
        std::vector<std::uint32_t> wanted;
        for (int warm = 0; warm < 2; ++warm)  // the first cycle warms the rows up
            for (int f = 0; f < kCycle; ++f) {
                const double time = f * kFrameStep;
                DrawList& list = lists[f];
                list.clear();
                if (cache) {
                    wanted.clear();
                    for (int i = 0; i < n; ++i) {
                        const KeyPoseSample s = cache->sample(0, phases[std::size_t(i)] + time);
                        samples[std::size_t(i)] = s;
                        wanted.push_back(s.a);
                        if (s.b != s.a) wanted.push_back(s.b);
                    }
                    std::sort(wanted.begin(), wanted.end());
                    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
                    const std::uint32_t updates = cache->rows().hold(wanted, std::uint64_t(warm * kCycle + f + 1));
                    if (warm == 1) fillsPerCycle += updates;
                }
                for (int i = 0; i < n; ++i) {
                    DrawItem item;
                    item.drawable = c.drawable.get();
                    item.actor = std::uint32_t(i);
                    if (cache) {
                        const KeyPoseSample& s = samples[std::size_t(i)];
                        item.representation = Representation::KeyPose;
                        item.keyPose.source = cache.get();
                        item.keyPose.skin = c.skin;
                        item.keyPose.pose[0] = s.a;
                        item.keyPose.pose[1] = s.b;
                        item.keyPose.row[0] = cache->rows().rowOf(s.a);
                        item.keyPose.row[1] = cache->rows().rowOf(s.b);
                        item.keyPose.blend = s.blend;
                        list.add(item, c.drawable->primitiveCount(), worlds[std::size_t(i)]);
                    } else if (mode == 4) {
                        list.add(item, c.drawable->primitiveCount(), worlds[std::size_t(i)]);
                    } else {
                        std::copy(t.restDofs().begin(), t.restDofs().end(), dofs.begin());
                        clip.sample(t, phases[std::size_t(i)] + time, true, {}, dofs);
                        computeModelTransforms(t, dofs, {}, model);
                        computeSkinPalette(t, t.skins()[c.skin], model, {}, palette);
                        list.add(item, c.drawable->primitiveCount(), worlds[std::size_t(i)], palette);
                    }
                }
            }
    }
};

std::shared_ptr<OsMesaContext> sharedContext() {
    static auto context = std::make_shared<OsMesaContext>(kWidth, kHeight);
    return context;
}

// One frame's cost: wall time, CPU time of every thread of the process (the main thread's vertex
// work and llvmpipe's rasteriser threads: the work done, which other load on the machine stretches
// far less than the wall time), CPU time of the calling thread alone.
struct FrameCost {
    double wallMs = 0, processMs = 0, threadMs = 0;
};

double cpuMs(clockid_t clock) {
    timespec t{};
    clock_gettime(clock, &t);
    return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

// Frame costs of every run of a case (all repetitions), for the summary.
std::map<std::pair<int, int>, std::vector<FrameCost>>& frameCosts() {
    static std::map<std::pair<int, int>, std::vector<FrameCost>> costs;
    return costs;
}

void BM_KeyPoseDraw(benchmark::State& state) {
    const int mode = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
    auto context = sharedContext();
    RendererOptions options;
    options.width = kWidth;
    options.height = kHeight;
    GlRenderer renderer(context, options);
    const Crowd crowd(n, mode);
    const auto frame = [&](int f) {
        if (mode == 3) renderer.releaseKeyPoses(*crowd.cache);
        renderer.beginFrame(crowd.camera);
        renderer.draw(crowd.lists[f]);
        renderer.endFrame();  // headless, present() is glFinish: the frame is rasterised inside the timing
    };
    for (int f = 0; f < kCycle; ++f) frame(f);  // warm-up: uploads, shader variants, rows
    if (const char* folder = std::getenv("THRONG_BENCH_FRAMES")) {
        renderer.beginFrame(crowd.camera);
        renderer.draw(crowd.lists[0]);
        writePng(renderer.readFrame(), std::string(folder) + "/keypose-" + kModeNames[mode] + "-" + std::to_string(n) + ".png");
        renderer.endFrame();
    }
    RenderStatistics totals;
    std::vector<FrameCost>& costs = frameCosts()[{mode, n}];
    int f = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        const double process = cpuMs(CLOCK_PROCESS_CPUTIME_ID), thread = cpuMs(CLOCK_THREAD_CPUTIME_ID);
        frame(f);
        costs.push_back({std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                         cpuMs(CLOCK_PROCESS_CPUTIME_ID) - process, cpuMs(CLOCK_THREAD_CPUTIME_ID) - thread});
        const RenderStatistics& s = renderer.statistics();
        totals.keyPoseFills += s.keyPoseFills;
        totals.drawMs += s.drawMs;
        f = (f + 1) % kCycle;
    }
    const RenderStatistics& s = renderer.statistics();
    const double frames = double(state.iterations());
    state.counters["instances"] = double(s.instances);
    state.counters["triangles"] = double(s.triangles);
    state.counters["draw_calls"] = double(s.drawCalls);
    state.counters["fills_per_frame"] = double(totals.keyPoseFills) / frames;
    state.counters["draw_cpu_ms"] = totals.drawMs / frames;
    state.counters["skinned_vertices"] = double(s.gpuSkinnedVertices);
    state.counters["cache_vertices"] = double(s.keyPoseVertices);
    state.counters["cache_MB"] = double(s.keyPoseCacheBytes) / 1e6;
    state.SetLabel(kModeNames[mode]);
}

BENCHMARK(BM_KeyPoseDraw)
    ->ArgNames({"mode", "instances"})
    ->ArgsProduct({{0, 1, 2, 3, 4}, {500, 2000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

// The summary: per case, the median and fastest frame by wall time and by CPU time of all threads,
// the main thread's CPU time, and the ratio skinned / case of the medians.
void printSummary() {
    using Field = double FrameCost::*;
    const auto median = [](const std::vector<FrameCost>& v, Field field) {
        std::vector<double> x;
        for (const FrameCost& c : v) x.push_back(c.*field);
        std::sort(x.begin(), x.end());
        return std::pair<double, double>(x[x.size() / 2], x.front());
    };
    std::printf("\nDRAW of N CesiumMan at 20-40 m, %dx%d, glFinish included, ms per frame (median / fastest);\n"
                "cpu = CPU time of every thread of the process, main = the drawing thread's; ratio = skinned / mode\n",
                kWidth, kHeight);
    std::printf("%-26s %5s %7s | %17s %6s | %17s %6s | %15s\n", "mode", "N", "frames", "wall med / min", "ratio",
                "cpu med / min", "ratio", "main med / min");
    for (const auto& [key, costs] : frameCosts()) {
        if (costs.empty()) continue;
        const auto base = frameCosts().find({0, key.second});
        const bool hasBase = base != frameCosts().end() && !base->second.empty();
        const auto [wall, wallMin] = median(costs, &FrameCost::wallMs);
        const auto [cpu, cpuMin] = median(costs, &FrameCost::processMs);
        const auto [mainMed, mainMin] = median(costs, &FrameCost::threadMs);
        const double wallRatio = hasBase ? median(base->second, &FrameCost::wallMs).first / wall : 0.0;
        const double cpuRatio = hasBase ? median(base->second, &FrameCost::processMs).first / cpu : 0.0;
        std::printf("%-26s %5d %7zu | %8.1f / %6.1f %6.2f | %8.1f / %6.1f %6.2f | %7.1f / %5.1f\n", kModeNames[key.first],
                    key.second, costs.size(), wall, wallMin, wallRatio, cpu, cpuMin, cpuRatio, mainMed, mainMin);
    }
}

}  // namespace
}  // namespace throng

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    throng::printSummary();
    return 0;
}
