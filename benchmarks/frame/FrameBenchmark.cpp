// bench_frame: the whole frame of the town crowd, every method on the identical state.
//
// Each tick the simulation steps once, outside every processor; then traditional processing,
// actor processing, and actor processing with far actors as impostors each run APP and CULL on
// that same state and DRAW their own list (1280 x 720 headless, the GL finished after each pass so
// every pass's time holds its rasterisation). The state digest (every actor's Reference Point)
// is taken after each method and must be the same for all methods of a tick: the program stops
// with an error if it is not. Columns: the step, APP, each CULL phase, poses, impostor selection
// and batching, morphing, the town's draw, the actors' meshes, the impostor quads, the whole frame.
//
// Two more sections, on identical states too: APP+CULL and the step with 1 and 2 threads (two
// worlds of the same seed, their digests compared), and end-to-end frames per second of the scene
// with DRAW overlapping the next frame (Performer's multiprocess mode) and without.
//
// `--sections regions` (not run by default): the shared step alone for large crowds (10k, 100k, 1M
// actors by default, the town grown at the scene's density), with one region and with the scene's
// regions, each with 1 and 2 threads, with the build time and the process's peak memory.
//
// `--sections town` (not run by default): the town's DRAW alone, the GL finished after the town
// pass, along the whole camera path (10 actors by default), with the old drawing, each improvement
// alone (front-to-back order, constant faces shaded per vertex, town LOD) and all together, the
// variants interleaved frame by frame on the same cameras; then where the default scene's pass goes
// (probes in the same rotation: clear and finish only, vertices and set-up only, depth only, one
// colour, no depth rejection), how many fragments it rasterises and keeps per frame, and how far an
// image cache of the town would be from the truth after the view moved a fraction of a pixel.
//
// usage: bench_frame --help

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <functional>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "throng/bench/Experiment.h"
#include "throng/bench/FrameWorld.h"
#include "throng/bench/ResultTable.h"
#include "throng/bench/SameState.h"
#include "throng/testkit/Assets.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/render/GlRenderer.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/render/ImpostorSet.h"
#include "throng/scenegraph/FramePipeline.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/sim/AccuracyCsv.h"

using namespace throng;

namespace {

using bench::bakeImpostors;
using bench::cameraTime;
using bench::impostorDistance;
using bench::stateDigest;

[[noreturn]] void fail(const std::string& why) { bench::fail("bench_frame", why); }

// The experiment's settings: the common ones (e: actor counts, cameras, measured ticks per camera,
// warm-up ticks so walkers spread along the streets, size, scene, outputs) and its own.
struct Options {
    bench::ExperimentSpec e;
    std::int64_t scalingActors = 10000;  // actors of the thread-scaling section (0: skip)
    int scalingFrames = 30;
    std::int64_t pipelineActors = 0;     // actors of the pipeline section (0: the scene's own count)
    int pipelineFrames = 120;            // frames of each pipeline run (0: skip)
    std::int64_t townActors = 10;        // actors of the town section
    int townSamples = 12;                // cameras along the path in the town section
    int townFrames = 5;                  // frames per camera and variant in the town section
    std::int64_t occlusionActors = 10000;  // actors of the occlusion-resolution section
    std::vector<int> occlusionRests;       // rest lengths of the occlusion section's resting rows (empty: the scene's)
    std::string occlusionCsv;              // where that section's rows go as CSV (empty: nowhere)
    bool occlusionPath = false;            // that section also follows the scene's camera path
    std::vector<std::int64_t> regionActors{10000, 100000, 1000000};  // crowds of the regions section
    int regionFrames = 40;                 // measured steps per thread count in the regions section
    std::vector<std::string> sections{"methods", "scaling", "pipeline"};
    bool has(const char* section) const { return std::find(sections.begin(), sections.end(), section) != sections.end(); }
};

const char* kMethods[] = {"traditional", "actor", "actor + impostors", "actor + occlusion", "actor + impostors + occlusion"};
constexpr int kMethodCount = 5;

// Means over the measured ticks of one method.
struct Row {
    std::int64_t actors = 0;
    std::string camera, method;
    double step = 0, app = 0, cull1 = 0, roots = 0, cull2 = 0, pose = 0, cull3 = 0, list = 0, appCull = 0;
    double batch = 0, morph = 0, town = 0, meshes = 0, quads = 0, finish = 0, draw = 0, frame = 0;
    double posed = 0, impostors = 0, items = 0, triangles = 0, occlusionBuffer = 0, hidden = 0;
    void add(double stepMs, const ActorFrameStatistics& s, const CrowdRenderStatistics& r, double drawMs) {
        step += stepMs;
        app += s.appMs + s.refpointMs + s.matricesBoundsMs;
        cull1 += s.cullMs + s.refpointOcclusionMs;
        occlusionBuffer += s.occlusionBufferMs;
        hidden += double(s.occludedWithGroup + s.occludedRefpoint + s.occludedSklsroot);
        roots += s.skeletonRootMs;
        cull2 += s.cull2Ms;
        pose += s.poseMs;
        cull3 += s.cull3Ms;
        list += s.drawListMs;
        appCull += s.appCullMs();
        batch += r.impostorBatchMs - r.morphMs;
        morph += r.morphMs;
        town += r.sceneMs;
        meshes += r.meshMs;
        quads += r.impostorDrawMs;
        finish += r.endFrameMs;
        draw += drawMs;
        frame += stepMs + s.appCullMs() + drawMs;
        posed += double(s.actorsPosed);
        impostors += double(s.impostors);
        items += double(s.drawItems);
        triangles += double(r.meshes.triangles);
    }
    void divide(double n) {
        for (double* v : {&step, &app, &cull1, &roots, &cull2, &pose, &cull3, &list, &appCull, &batch, &morph, &town, &meshes,
                          &quads, &finish, &draw, &frame, &posed, &impostors, &items, &triangles, &occlusionBuffer, &hidden})
            *v /= n;
    }
};

// The methods on the same ticks, for each camera.
std::vector<Row> compareMethods(const Options& o, std::int64_t actors, const std::shared_ptr<GlContext>& context,
                                std::uint64_t* ticksChecked) {
    auto world = bench::buildWorld(o.e.scene, actors);
    auto impostors = bakeImpostors(context, *world);
    context->resize(o.e.width, o.e.height);
    ActorProcessor traditional(world->crowd()), actor(world->crowd()), hybrid(world->crowd()), occluding(world->crowd()),
        hybridOccluding(world->crowd());
    traditional.setProcessing(Processing::Traditional);
    const auto [distance, hysteresis] = impostorDistance(*world);
    impostors->attach(hybrid, distance, hysteresis);
    impostors->attach(hybridOccluding, distance, hysteresis);
    const OcclusionSettings occlusion = world->description().representation.occlusion.value_or(OcclusionSettings{});
    occluding.setOcclusion(occlusion);
    hybridOccluding.setOcclusion(occlusion);
    ActorProcessor* processors[] = {&traditional, &actor, &hybrid, &occluding, &hybridOccluding};
    CrowdRendererOptions ro;
    ro.finishPasses = true;
    CrowdRenderer renderer(context, ro);
    for (int f = 0; f < o.e.warmup; ++f) world->step();
    std::vector<Row> rows;
    for (const std::string& cameraName : o.e.cameras) {
        const Camera camera = world->camera().at(cameraTime(cameraName), double(o.e.width) / double(o.e.height));
        Row r[kMethodCount];
        for (int m = 0; m < kMethodCount; ++m) {
            r[m].actors = std::int64_t(world->crowd().size());
            r[m].camera = cameraName;
            r[m].method = kMethods[m];
        }
        for (int f = -2; f < o.e.frames; ++f) {  // two unmeasured ticks warm every method's caches
            const FrameContext& now = world->step();
            const double stepMs = world->lastStepMs();
            bench::runOnSameState(world->crowd(), kMethodCount, f + 2, [&](std::size_t m) {
                const ActorFrameStatistics s = processors[m]->processFrame(world->root(), camera, now.time);
                Stopwatch watch;
                renderer.drawFrame(camera, processors[m]->drawList());
                const double drawMs = watch.elapsedMs();
                if (f >= 0) r[m].add(stepMs, s, renderer.statistics(), drawMs);
            }, [&](std::size_t m) { return kMethods[m]; });
            if (f >= 0) ++*ticksChecked;
        }
        for (Row& row : r) {
            row.divide(o.e.frames);
            rows.push_back(row);
        }
        std::fprintf(stderr, "bench_frame: %lld actors, %s camera done\n", (long long)actors, cameraName.c_str());
    }
    return rows;
}

// What a perfect occlusion culler could reach: an ID render with full depth (every actor posed at
// full detail, each actor and the town in flat colours) gives the actors with a visible pixel;
// a conservative culler must keep every one of them, so "actors drawn as meshes without occlusion"
// over "those of them with a visible pixel" bounds the reduction any occlusion culling can give.
struct VisibilityRow {
    std::string camera, method;
    std::size_t meshActors = 0;     // actors drawn as meshes without occlusion
    std::size_t visible = 0;        // of those, with a visible pixel
    std::size_t visibleTown = 0;    // of those, with a pixel the town alone leaves visible
    std::size_t withOcclusion = 0;  // actors drawn as meshes with occlusion
};

constexpr int kTownGroups = 16;

std::vector<VisibilityRow> visibilityBound(const Options& o, const std::shared_ptr<GlContext>& context, std::int64_t* actors) {
    auto world = bench::buildWorld(o.e.scene, o.occlusionActors);
    auto impostors = bakeImpostors(context, *world);
    context->resize(o.e.width, o.e.height);
    *actors = std::int64_t(world->crowd().size());
    const auto [distance, hysteresis] = impostorDistance(*world);
    const OcclusionSettings occlusion = world->description().representation.occlusion.value_or(OcclusionSettings{});
    ActorProcessor full(world->crowd()), plain(world->crowd()), plainOccluding(world->crowd()), hybrid(world->crowd()),
        hybridOccluding(world->crowd());
    full.setProcessing(Processing::Traditional);
    full.setLodScale(1e-6);
    plainOccluding.setOcclusion(occlusion);
    hybridOccluding.setOcclusion(occlusion);
    impostors->attach(hybrid, distance, hysteresis);
    impostors->attach(hybridOccluding, distance, hysteresis);
    RendererOptions ids;
    ids.flatTint = true;
    ids.clearColor = glm::vec4(0.0f);
    GlRenderer renderer(context, ids);
    for (int f = 0; f < o.e.warmup; ++f) world->step();
    const double time = world->now().time;
    // Six bits of the ID per channel, mid-step: the GL's rounding cannot change the ID read back.
    const auto colour = [](std::uint32_t id) {
        const auto level = [&](int shift) { return float(4 * ((id >> shift) & 0x3F) + 2) / 255.0f; };
        return glm::vec4(level(0), level(6), level(12), 1.0f);
    };
    const std::uint32_t town = 1u << 17;
    const auto meshActors = [](const DrawList& list) {
        std::set<std::uint32_t> a;
        for (const DrawItem& item : list.items())
            if (item.actor != kNoActor && item.representation != Representation::Impostor) a.insert(item.actor);
        return a;
    };
    std::vector<VisibilityRow> rows;
    for (const std::string& cameraName : o.e.cameras) {
        const Camera camera = world->camera().at(cameraTime(cameraName), double(o.e.width) / double(o.e.height));
        full.processFrame(world->root(), camera, time);
        // Group -1: every actor at once (actors hide actors). Groups 0-15: the town and every
        // sixteenth actor, so actors hardly hide each other: what the town alone leaves visible.
        std::set<std::uint32_t> visible, visibleTown;
        for (int group = -1; group < kTownGroups; ++group) {
            DrawList list;
            for (const DrawItem& item : full.drawList().items()) {
                if (group >= 0 && item.actor != kNoActor && int(item.actor % kTownGroups) != group) continue;
                DrawItem tinted = item;
                tinted.tint = colour(item.actor != kNoActor ? item.actor + 1 : town);
                list.add(tinted, 0);
            }
            renderer.beginFrame(camera);
            renderer.draw(list);
            const Image image = renderer.readFrame();
            renderer.endFrame();
            for (std::size_t p = 0; p < image.rgba.size(); p += 4) {
                const std::uint32_t id = (image.rgba[p] / 4u) | ((image.rgba[p + 1] / 4u) << 6) | ((image.rgba[p + 2] / 4u) << 12);
                if (id != 0 && id != town && id - 1 < world->crowd().size()) (group < 0 ? visible : visibleTown).insert(id - 1);
            }
        }
        const std::pair<ActorProcessor*, ActorProcessor*> pairs[] = {{&plain, &plainOccluding}, {&hybrid, &hybridOccluding}};
        const char* names[] = {"actor", "actor + impostors"};
        for (int k = 0; k < 2; ++k) {
            pairs[k].first->processFrame(world->root(), camera, time);
            const std::set<std::uint32_t> drawn = meshActors(pairs[k].first->drawList());
            pairs[k].second->processFrame(world->root(), camera, time);
            VisibilityRow r{cameraName, names[k], drawn.size(), 0, 0, meshActors(pairs[k].second->drawList()).size()};
            for (std::uint32_t a : drawn) r.visible += visible.count(a), r.visibleTown += visibleTown.count(a);
            rows.push_back(r);
        }
    }
    return rows;
}

// APP+CULL and the step with 1 and 2 threads, on two worlds of the same seed.
struct Scaling {
    std::string camera;
    double step[2] = {}, actor[2] = {}, traditional[2] = {};
};

std::vector<Scaling> threadScaling(const Options& o) {
    std::unique_ptr<sim::Simulation> worlds[2] = {bench::buildWorld(o.e.scene, o.scalingActors), bench::buildWorld(o.e.scene, o.scalingActors)};
    std::unique_ptr<ActorProcessor> actor[2], traditional[2];
    for (int k = 0; k < 2; ++k) {
        worlds[k]->setThreads(unsigned(k + 1));
        actor[k] = std::make_unique<ActorProcessor>(worlds[k]->crowd());
        traditional[k] = std::make_unique<ActorProcessor>(worlds[k]->crowd());
        actor[k]->setThreads(unsigned(k + 1));
        traditional[k]->setThreads(unsigned(k + 1));
        traditional[k]->setProcessing(Processing::Traditional);
        for (int f = 0; f < o.e.warmup; ++f) worlds[k]->step();
    }
    std::vector<Scaling> out;
    for (const std::string& cameraName : o.e.cameras) {
        Scaling s;
        s.camera = cameraName;
        const Camera camera = worlds[0]->camera().at(cameraTime(cameraName), double(o.e.width) / double(o.e.height));
        for (int f = -2; f < o.scalingFrames; ++f) {
            std::uint64_t digest[2] = {};
            for (int i = 0; i < 2; ++i) {
                const int k = (f + 2 + i) % 2;  // alternate which thread count goes first
                const double t = worlds[k]->step().time;
                const double stepMs = worlds[k]->lastStepMs();
                const double a = actor[k]->processFrame(worlds[k]->root(), camera, t).appCullMs();
                const double tr = traditional[k]->processFrame(worlds[k]->root(), camera, t).appCullMs();
                digest[k] = stateDigest(worlds[k]->crowd());
                if (f >= 0) {
                    s.step[k] += stepMs / o.scalingFrames;
                    s.actor[k] += a / o.scalingFrames;
                    s.traditional[k] += tr / o.scalingFrames;
                }
            }
            if (digest[0] != digest[1]) fail("thread scaling: 1 and 2 threads reached different states at tick " + std::to_string(f));
        }
        out.push_back(s);
    }
    return out;
}

// The shared step of a large crowd with one region or the scene's, with 1 and 2 threads.
struct RegionRow {
    std::int64_t actors = 0;
    std::string layout, note;
    std::uint32_t regions = 0;
    double ms[2] = {};
    double ghosts = 0, handovers = 0, buildSeconds = 0, peakGb = 0;
};

double peakMemoryGb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / (1024.0 * 1024.0);
}

// How much faster a loop with nothing shared runs on 2 threads than on 1 right now: what the
// machine (shared with other work) can give, to read the step's speed-up against.
double availableSpeedup() {
    double ms[2] = {};
    for (int round = 0; round < 2; ++round)
        for (int k = 0; k < 2; ++k) {
            ThreadTeam team(unsigned(k + 1));
            Stopwatch watch;
            team.run([] {
                forEachChunk(16, 1, [](std::size_t, std::size_t, std::size_t) {
                    volatile double x = 0.0;
                    for (int i = 0; i < 4'000'000; ++i) x = x + 1.0;
                });
            });
            ms[k] += watch.elapsedMs();
        }
    return ms[0] / ms[1];
}

std::vector<RegionRow> regionSweep(const Options& o) {
    std::vector<RegionRow> out;
    for (std::int64_t n : o.regionActors)
        for (bool one : {true, false}) {
            RegionRow r;
            r.actors = n;
            r.layout = one ? "one region" : "the scene's regions";
            sim::SceneDescription d = sim::parseSceneFile(o.e.scene);
            try {
                sim::scaleActors(d, n);
            } catch (const std::invalid_argument& e) {
                r.note = std::string("refused: ") + e.what();
                out.push_back(r);
                continue;
            }
            std::int64_t walkers = 0;
            for (const auto& g : d.actors) walkers += g.behaviour == "walk" ? g.count : 0;
            if (one && d.town) {
                d.town->regions.clear();
                d.town->regionBlocks = {d.town->blocksX, d.town->blocksZ};
                if (walkers > 40000) {  // Locomotion refuses it before stepping: do not build it
                    r.note = "not run: one DetourCrowd numbers agents with 16 bits";
                    out.push_back(r);
                    continue;
                }
            }
            std::fprintf(stderr, "bench_frame: %lld actors, %s: building...\n", (long long)n, r.layout.c_str());
            const auto t0 = std::chrono::steady_clock::now();
            std::unique_ptr<sim::Simulation> world;
            try {
                world = sim::Simulation::build(std::move(d));
            } catch (const std::exception& e) {
                r.note = std::string("build failed: ") + e.what();
                out.push_back(r);
                continue;
            }
            r.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            r.regions = world->locomotion() ? world->locomotion()->regionCount() : 0;
            for (int f = 0; f < o.e.warmup; ++f) world->step();
            // Two rounds of 1 then 2 threads, so that a drift of the machine's load falls on both.
            const int half = std::max(1, o.regionFrames / 2);
            for (int round = 0; round < 2; ++round)
                for (int k = 0; k < 2; ++k) {
                    world->setThreads(unsigned(k + 1));
                    for (int f = 0; f < half; ++f) {
                        world->step();
                        r.ms[k] += world->lastStepMs() / (2.0 * half);
                        if (world->locomotion()) {
                            r.ghosts += double(world->locomotion()->lastGhostCount()) / (4.0 * half);
                            r.handovers += double(world->locomotion()->lastHandoverCount()) / (4.0 * half);
                        }
                    }
                }
            r.peakGb = peakMemoryGb();
            out.push_back(r);
        }
    return out;
}

// End-to-end frames per second as throng-town runs (step, APP/CULL, DRAW with impostors, street
// camera following the path), with DRAW overlapping the next frame and without; two worlds of the
// same seed run in alternating blocks.
struct PipelineResult {
    double fps[2] = {};  // off, on
    std::int64_t actors = 0;
};

PipelineResult pipelineFps(const Options& o, const std::shared_ptr<GlContext>& context) {
    struct Run {
        std::unique_ptr<sim::Simulation> world;
        std::unique_ptr<ActorProcessor> processor;
        std::unique_ptr<FramePipeline> pipeline;
        double seconds = 0;
        std::int64_t frames = 0;
    } runs[2];
    auto impostors = [&] {
        auto world = bench::buildWorld(o.e.scene, o.pipelineActors);
        return bakeImpostors(context, *world);
    }();
    context->resize(o.e.width, o.e.height);
    CrowdRenderer renderer(context);
    const double aspect = double(o.e.width) / double(o.e.height);
    PipelineResult result;
    for (int k = 0; k < 2; ++k) {
        Run& r = runs[k];
        r.world = bench::buildWorld(o.e.scene, o.pipelineActors);
        r.processor = std::make_unique<ActorProcessor>(r.world->crowd());
        r.pipeline = std::make_unique<FramePipeline>(k == 1);
        // The same templates, baked once: the processor only needs the drawables of its templates.
        const auto [distance, hysteresis] = impostorDistance(*r.world);
        for (std::size_t i = 0; i < r.world->templates().size(); ++i)
            r.processor->setImpostor(*r.world->templates()[i].tmpl, impostors->drawable(i));
        r.processor->setImpostorDistance(distance, hysteresis);
        result.actors = std::int64_t(r.world->crowd().size());
    }
    // Each block: prepare the first frame, then overlap (or not) DRAW of each frame with the next.
    auto block = [&](Run& r, int frames) {
        const DrawList* lists[2] = {};
        Camera cameras[2];
        auto prepare = [&](int slot) {
            const double t = r.world->step().time;
            cameras[slot] = r.world->camera().at(std::min(t + 9.0, r.world->camera().duration()), aspect);
            r.processor->processFrame(r.world->root(), cameras[slot], t);
            lists[slot] = &r.processor->drawList();
        };
        const auto start = std::chrono::steady_clock::now();
        prepare(0);
        for (int f = 0; f < frames; ++f) {
            r.pipeline->run([&] { if (f + 1 < frames) prepare((f + 1) % 2); },
                            [&] { renderer.drawFrame(cameras[f % 2], *lists[f % 2]); });
        }
        r.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        r.frames += frames;
    };
    for (int k = 0; k < 2; ++k) {
        for (int f = 0; f < o.e.warmup; ++f) runs[k].world->step();
        block(runs[k], std::min(o.pipelineFrames, 10));  // first uploads, morph cache: not measured
        runs[k].seconds = 0;
        runs[k].frames = 0;
    }
    for (int b = 0; b < 4; ++b) block(runs[b % 2], std::max(o.pipelineFrames / 2, 1));
    for (int k = 0; k < 2; ++k) result.fps[k] = double(runs[k].frames) / runs[k].seconds;
    return result;
}

// One occlusion buffer resolution on one camera: what it rejected and what it cost.
struct OcclusionRow {
    std::string camera;
    int width = 0, height = 0;  // 0 x 0: occlusion off
    int rest = 0;               // OcclusionSettings::restFrames (0: tests every frame)
    double bufferMs = 0, appCullMs = 0, hidden = 0, reachingCull1 = 0, posed = 0, tiles = 0, rested = 0;
    double hiddenShare() const { return reachingCull1 > 0 ? hidden / reachingCull1 : 0.0; }
    std::string label() const {
        if (!width) return "off";
        return std::to_string(width) + "x" + std::to_string(height) + (rest ? ", rest " + std::to_string(rest) : "");
    }
};

// The occlusion buffer's resolution against rejection and time (actor + impostors processing, the
// same ticks for every resolution and for occlusion off, in turns), and the scene's resolution resting after
// frames that hid little (the scene's rest, or 8 frames with the default limits, or each length of
// --occlusion-rests). The "path" camera
// follows the scene's camera path once, tick by tick, so rests end as they would in the example.
std::vector<OcclusionRow> occlusionSweep(const Options& o, const std::shared_ptr<GlContext>& context, std::int64_t* actorsOut) {
    auto world = bench::buildWorld(o.e.scene, o.occlusionActors);
    const OcclusionSettings declared = world->description().representation.occlusion.value_or(OcclusionSettings{});
    struct Variant {
        int width, height, rest;
    };
    std::vector<Variant> variants = {{0, 0, 0}, {64, 36, 0}, {128, 72, 0}, {256, 144, 0}, {512, 288, 0}, {1024, 576, 0}};
    for (int rest : o.occlusionRests.empty() ? std::vector<int>{declared.restFrames > 0 ? declared.restFrames : 8} : o.occlusionRests)
        variants.push_back({declared.width, declared.height, rest});
    *actorsOut = std::int64_t(world->crowd().size());
    auto impostors = bakeImpostors(context, *world);
    const auto [distance, hysteresis] = impostorDistance(*world);
    std::vector<std::unique_ptr<ActorProcessor>> processors;
    for (const Variant& v : variants) {
        processors.push_back(std::make_unique<ActorProcessor>(world->crowd()));
        impostors->attach(*processors.back(), distance, hysteresis);
        if (v.width > 0) {
            OcclusionSettings settings = declared;
            settings.width = v.width, settings.height = v.height, settings.restFrames = v.rest;
            processors.back()->setOcclusion(settings);
        }
    }
    for (int f = 0; f < o.e.warmup; ++f) world->step();
    std::vector<OcclusionRow> rows;
    std::vector<std::string> cameras = o.e.cameras;
    if (o.occlusionPath) cameras.push_back("path");
    const double aspect = double(o.e.width) / double(o.e.height);
    for (const std::string& cameraName : cameras) {
        const bool path = cameraName == "path";
        const int frames = path ? int(std::ceil(world->camera().duration() / world->description().step)) + 1 : o.e.frames;
        std::vector<OcclusionRow> r(variants.size());
        for (std::size_t k = 0; k < variants.size(); ++k)
            r[k].camera = cameraName, r[k].width = variants[k].width, r[k].height = variants[k].height, r[k].rest = variants[k].rest;
        for (int f = -2; f < frames; ++f) {
            const FrameContext& now = world->step();
            const Camera camera = world->camera().at(path ? std::max(f, 0) * world->description().step : cameraTime(cameraName), aspect);
            // Each tick starts with another variant, so none always runs on caches its predecessor warmed.
            for (std::size_t i = 0; i < variants.size(); ++i) {
                const std::size_t k = (i + std::size_t(f + 2)) % variants.size();
                const ActorFrameStatistics s = processors[k]->processFrame(world->root(), camera, now.time);
                if (f < 0) continue;
                r[k].bufferMs += s.occlusionBufferMs;
                r[k].appCullMs += s.appCullMs();
                r[k].hidden += double(s.occludedWithGroup + s.occludedRefpoint + s.occludedSklsroot);
                r[k].reachingCull1 += double(s.actorsInScene - s.culledWithGroup - s.a);
                r[k].posed += double(s.actorsPosed);
                r[k].tiles += double(s.nodesOccluded);
                r[k].rested += s.occlusionRested ? 1.0 : 0.0;
            }
        }
        for (OcclusionRow& row : r) {
            for (double* v : {&row.bufferMs, &row.appCullMs, &row.hidden, &row.reachingCull1, &row.posed, &row.tiles, &row.rested})
                *v /= frames;
            rows.push_back(row);
        }
        std::fprintf(stderr, "bench_frame: occlusion resolutions, %s camera done\n", cameraName.c_str());
    }
    return rows;
}

// The town's DRAW alone: the old drawing, each improvement alone and all together.
struct TownVariant {
    std::string name;
    bool frontToBack = false, constantFaces = false, lod = false, occlusion = false;
    bool clearOnly = false;                  // probe: clear and finish, no item drawn
    DrawProbe probe = DrawProbe::None;       // probe: work the renderer leaves out
    std::vector<double> ms{};       // mean town pass per camera sample (wall clock)
    std::vector<double> cpuMs{};    // the same in CPU time of the whole process (every GL thread)
    double triangles = 0;           // mean town triangles drawn per frame
    bool isProbe() const { return clearOnly || probe != DrawProbe::None; }
    /// Drawn as the default scene draws its town (a probe of it too).
    bool asDefaultScene() const { return frontToBack && constantFaces && !lod && occlusion; }
    /// Which of townDraw's lists it draws: full tiles or LOD tiles, without or with occlusion.
    std::size_t list() const { return (lod ? 1 : 0) + (occlusion ? 2 : 0); }
};

std::vector<TownVariant> townVariants() {
    std::vector<TownVariant> v;
    v.push_back({.name = "old drawing"});
    v.push_back({.name = "front to back", .frontToBack = true});
    v.push_back({.name = "constant faces", .constantFaces = true});
    v.push_back({.name = "town LOD", .lod = true});
    v.push_back({.name = "occlusion culling", .occlusion = true});
    v.push_back({.name = "front to back + constant faces", .frontToBack = true, .constantFaces = true});
    v.push_back({.name = "front to back + constant faces + occlusion (default scene)", .frontToBack = true, .constantFaces = true, .occlusion = true});
    v.push_back({.name = "all together", .frontToBack = true, .constantFaces = true, .lod = true, .occlusion = true});
    // Probes of the default scene's pass: the same list with part of the work left out.
    const auto probe = [&](const char* name, bool clearOnly, DrawProbe p) {
        v.push_back({.name = name, .frontToBack = true, .constantFaces = true, .occlusion = true, .clearOnly = clearOnly, .probe = p});
    };
    probe("clear and finish only", true, DrawProbe::None);
    probe("vertices and set-up only (scissored to 8 x 8 pixels)", false, DrawProbe::SetUpOnly);
    probe("depth only (colour writes off)", false, DrawProbe::DepthOnly);
    probe("one colour (the same fragments, per-pixel shading left out)", false, DrawProbe::OneColour);
    probe("no depth rejection (every fragment shaded)", false, DrawProbe::NoDepthRejection);
    return v;
}

// The town's items of a draw list (no actor, drawn as meshes), as CrowdRenderer's first pass takes them.
void townItems(const DrawList& list, DrawList& town) {
    town.clear();
    for (const DrawItem& item : list.items())
        if (item.actor == kNoActor && item.representation != Representation::Impostor) town.add(item, 0);
}

// CPU time of the whole process (the GL's rasteriser threads included), in milliseconds.
double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// Town LOD levels measured when the scene declares none: full tiles to 50 m, half the triangles to
// 100 m, a quarter beyond.
const std::vector<glm::dvec2> kTownLod{{50.0, 1.0}, {100.0, 0.5}, {std::numeric_limits<double>::infinity(), 0.25}};

// Sub-pixel displacements of the view, in pixels, at which a cached image of the town is compared
// with the town drawn again.
constexpr double kReuseOffsets[] = {0.1, 0.25, 0.5};

// How far a cached image of the town is from the truth after the view moved a fraction of a pixel,
// over the sampled cameras: shown as it was (nearest texel), or resampled to follow (bilinear).
struct ImageReuse {
    std::vector<double> keptOver;    // share of pixels over 8/255, the cached image unchanged
    std::vector<double> shiftedOver; // the same, the cached image shifted bilinearly by the offset
    std::vector<double> keptPsnr, shiftedPsnr;
};

struct TownResult {
    std::vector<TownVariant> variants;
    std::vector<double> times;      // camera path times sampled
    std::vector<double> rasterised; // the default scene's town fragments per camera, in screens (depth test always passes)
    std::vector<double> passing;    // of those, passing the depth test as drawn (front to back), in screens
    bool lodDeclared = false;
    // What an image cache of the town would have to stay under (see townImageReuse).
    std::vector<ImageReuse> reuse;  // one per sub-pixel offset in kReuseOffsets
    std::vector<double> turnPixels; // the view's turn from one tick to the next along the path, in pixels at the centre
};

// Fragments of one town pass (back faces culled) that reach the depth test, and that pass it as
// drawn, each in screens (fragments / pixels).
std::pair<double, double> townFragments(GlRenderer& r, const Camera& camera, const DrawList& list) {
    const RendererOptions drawn = r.options();
    double screens[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
        RendererOptions counting = drawn;
        counting.countFragments = true;
        counting.probe = k == 0 ? DrawProbe::NoDepthRejection : DrawProbe::None;
        r.setOptions(counting);
        r.beginFrame(camera);
        r.draw(list);
        screens[k] = double(r.statistics().fragments) / (double(r.width()) * double(r.height()));
        r.endFrame();
    }
    r.setOptions(drawn);
    return {screens[0], screens[1]};
}

// `image` moved `dx` pixels to the right (0 <= dx < 1), sampled bilinearly; the first column repeats.
Image shiftedRight(const Image& image, double dx) {
    Image out = image;
    const std::size_t row = std::size_t(image.width) * 4;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 4; ++c) {
                const std::size_t at = std::size_t(y) * row + std::size_t(x) * 4 + std::size_t(c);
                const double left = image.rgba[x > 0 ? at - 4 : at], here = image.rgba[at];
                out.rgba[at] = static_cast<std::uint8_t>(std::lround(dx * left + (1.0 - dx) * here));
            }
    return out;
}

// `camera` with its image moved `dx` pixels to the right (the view turned by that much, to first
// order): a translation in clip space after the projection.
Camera shiftedCamera(const Camera& camera, double dx, int width) {
    Camera c = camera;
    c.setProjectionMatrix(glm::translate(Mat4(1.0), Vec3(2.0 * dx / width, 0.0, 0.0)) * camera.projection());
    return c;
}

// The default scene's town pass from `camera`, and again with the view moved by each of
// kReuseOffsets: how much a cached image would be off, kept or shifted to follow (golden-image
// threshold 8/255).
void townImageReuse(GlRenderer& r, const Camera& camera, const DrawList& list, std::vector<ImageReuse>& reuse) {
    const auto frame = [&](const Camera& c) {
        r.beginFrame(c);
        r.draw(list);
        Image image = r.readFrame();
        r.endFrame();
        return image;
    };
    const Image cached = frame(camera);
    reuse.resize(std::size(kReuseOffsets));
    for (std::size_t i = 0; i < std::size(kReuseOffsets); ++i) {
        const Image truth = frame(shiftedCamera(camera, kReuseOffsets[i], r.width()));
        const testkit::ImageDifference kept = testkit::compareImages(cached, truth, 8), shifted = testkit::compareImages(shiftedRight(cached, kReuseOffsets[i]), truth, 8);
        reuse[i].keptOver.push_back(kept.fractionOverThreshold);
        reuse[i].shiftedOver.push_back(shifted.fractionOverThreshold);
        reuse[i].keptPsnr.push_back(kept.psnr);
        reuse[i].shiftedPsnr.push_back(shifted.psnr);
    }
}

// The view's turn from each tick of `path` to the next, in pixels at the image centre.
std::vector<double> pathTurnPixels(const sim::CameraPath& path, double step, double aspect, int height) {
    std::vector<double> turns;
    const auto forward = [&](double t) {
        const Mat4 inverse = glm::inverse(path.at(t, aspect).view());
        return glm::normalize(Vec3(inverse * glm::dvec4(0.0, 0.0, -1.0, 0.0)));
    };
    const double pixel = path.at(0.0, aspect).fovY() / height;
    Vec3 before = forward(0.0);
    for (double t = step; t <= path.duration(); t += step) {
        const Vec3 now = forward(t);
        turns.push_back(std::acos(std::clamp(glm::dot(before, now), -1.0, 1.0)) / pixel);
        before = now;
    }
    return turns;
}

TownResult townDraw(const Options& o, const std::shared_ptr<GlContext>& context) {
    // Two worlds of one seed: the town as declared (with its LOD, if any) and at full detail.
    sim::SceneDescription scene = sim::parseSceneFile(o.e.scene);
    sim::scaleActors(scene, o.townActors);
    TownResult result;
    if (!scene.town) fail("--sections town: the scene declares no town");
    result.lodDeclared = !scene.town->lod.empty();
    if (!result.lodDeclared) scene.town->lod = kTownLod;
    scene.town->lodScale = 0.0;  // the levels at their declared distances (a scene may keep them for a frame budget)
    sim::SceneDescription full = scene;
    full.town->lod.clear();
    std::unique_ptr<sim::Simulation> worlds[2] = {sim::Simulation::build(std::move(full)), sim::Simulation::build(std::move(scene))};
    context->resize(o.e.width, o.e.height);
    // Lists: full tiles, LOD tiles, then each of them with the tiles occlusion hides left out.
    std::unique_ptr<ActorProcessor> processors[4];
    const OcclusionSettings occlusion = worlds[0]->description().representation.occlusion.value_or(OcclusionSettings{});
    for (int w = 0; w < 2; ++w) {
        if (!worlds[w]) continue;
        processors[w] = std::make_unique<ActorProcessor>(worlds[w]->crowd());
        processors[w + 2] = std::make_unique<ActorProcessor>(worlds[w]->crowd());
        processors[w + 2]->setOcclusion(occlusion);
        for (int f = 0; f < std::max(o.e.warmup, 1); ++f) worlds[w]->step();
    }
    result.variants = townVariants();
    // The town pass alone: clear, draw the town's items, finish (endFrame waits for the GL).
    std::vector<std::unique_ptr<GlRenderer>> renderers;
    for (const TownVariant& v : result.variants) {
        RendererOptions ro;
        ro.frontToBack = v.frontToBack;
        ro.constantFaces = v.constantFaces;
        ro.probe = v.probe;
        renderers.push_back(std::make_unique<GlRenderer>(context, ro));
    }
    DrawList lists[4];
    const double aspect = double(o.e.width) / double(o.e.height), duration = worlds[0]->camera().duration();
    const std::size_t nv = result.variants.size();
    std::vector<double> wall(nv), cpu(nv);  // this sample's sums per variant
    const std::size_t defaultVariant = std::size_t(std::find_if(result.variants.begin(), result.variants.end(), [](const TownVariant& v) {
        return v.asDefaultScene() && !v.isProbe();
    }) - result.variants.begin());
    for (int sample = -1; sample < o.townSamples; ++sample) {  // sample -1: uploads and JIT, not measured
        const double t = duration * (std::max(sample, 0) + 0.5) / o.townSamples;
        const Camera camera = worlds[0]->camera().at(t, aspect);
        for (int w = 0; w < 4; ++w) {
            if (!processors[w]) continue;
            processors[w]->processFrame(worlds[w % 2]->root(), camera, worlds[w % 2]->now().time);
            townItems(processors[w]->drawList(), lists[w]);
        }
        std::fill(wall.begin(), wall.end(), 0.0);
        std::fill(cpu.begin(), cpu.end(), 0.0);
        for (int f = 0; f < o.townFrames; ++f) {
            for (std::size_t i = 0; i < nv; ++i) {
                const std::size_t k = (i + std::size_t(f)) % nv;  // rotate which variant goes first
                GlRenderer& r = *renderers[k];
                r.beginFrame(camera);
                const double cpu0 = processCpuMs();
                Stopwatch watch;
                if (!result.variants[k].clearOnly) r.draw(lists[result.variants[k].list()]);
                r.endFrame();
                wall[k] += watch.elapsedMs();
                cpu[k] += processCpuMs() - cpu0;
                if (sample >= 0) result.variants[k].triangles += double(r.statistics().triangles) / (o.townFrames * o.townSamples);
            }
        }
        if (sample < 0) continue;
        const DrawList& defaultList = lists[result.variants[defaultVariant].list()];
        const auto [rasterised, passing] = townFragments(*renderers[defaultVariant], camera, defaultList);
        townImageReuse(*renderers[defaultVariant], camera, defaultList, result.reuse);
        result.rasterised.push_back(rasterised);
        result.passing.push_back(passing);
        result.times.push_back(t);
        for (std::size_t k = 0; k < nv; ++k) {
            result.variants[k].ms.push_back(wall[k] / o.townFrames);
            result.variants[k].cpuMs.push_back(cpu[k] / o.townFrames);
        }
    }
    result.turnPixels = pathTurnPixels(worlds[0]->camera(), worlds[0]->description().step, aspect, o.e.height);
    return result;
}

std::string townTable(const TownResult& r, const Options& o, const std::string& gl) {
    std::ostringstream t;
    char line[1024];
    auto mean = [](const std::vector<double>& v) {
        double s = 0;
        for (double x : v) s += x;
        return v.empty() ? 0.0 : s / double(v.size());
    };
    t << "Town DRAW alone (the GL finished after the town pass), " << o.townActors << " actors, " << o.e.width << " x " << o.e.height
      << " headless, " << gl << "; " << r.times.size() << " cameras along the path, " << o.townFrames
      << " frames each per variant, variants interleaved:\n\n";
    bench::ResultTable variants({{"", "variant", "%s", true}, {"", "mean ms", "%.1f"}, {"", "worst camera ms", "%.1f"}, {"", "vs old", "%.2fx"},
                                 {"", "CPU ms (all threads)", "%.1f"}, {"", "town triangles", "%.0f"}});
    const double old = mean(r.variants.front().ms);
    for (const TownVariant& v : r.variants)
        if (!v.isProbe())
            variants.add({v.name, mean(v.ms), *std::max_element(v.ms.begin(), v.ms.end()), old / mean(v.ms), mean(v.cpuMs), v.triangles});
    t << variants.markdown();
    // Where the default scene's pass goes: the same list and renderer with part of the work left out.
    t << "\nWhere the default scene's town pass goes (its list and renderer, part of the work left out; the same frames):\n\n";
    bench::ResultTable probes({{"", "probe", "%s", true}, {"", "mean ms", "%.1f"}, {"", "share of the whole pass", "%.0f %%"},
                               {"", "CPU ms (all threads)", "%.1f"}});
    double whole = 0;
    for (const TownVariant& v : r.variants)
        if (!v.isProbe() && v.asDefaultScene()) whole = mean(v.ms);
    for (const TownVariant& v : r.variants)
        if (v.asDefaultScene())
            probes.add({!v.isProbe() ? std::string("the whole pass") : v.name, mean(v.ms), 100.0 * mean(v.ms) / std::max(whole, 1e-9), mean(v.cpuMs)});
    t << probes.markdown();
    std::snprintf(line, sizeof line,
                  "\nFragments per frame, in screens of %d x %d pixels (back faces culled): %.2f reach the depth test (%.2f to %.2f over the "
                  "cameras), %.2f pass it as drawn front to back.\n",
                  o.e.width, o.e.height, mean(r.rasterised), *std::min_element(r.rasterised.begin(), r.rasterised.end()),
                  *std::max_element(r.rasterised.begin(), r.rasterised.end()), mean(r.passing));
    t << line;
    // What an image cache (drawing the town once and showing it again) would have to stay under.
    std::vector<double> turns = r.turnPixels;
    std::sort(turns.begin(), turns.end());
    const auto turnedAtLeast = [&](double px) {
        return 100.0 * double(turns.end() - std::lower_bound(turns.begin(), turns.end(), px)) / double(std::max<std::size_t>(turns.size(), 1));
    };
    if (!turns.empty()) {
        std::snprintf(line, sizeof line,
                      "\nAn image cache of the town (drawn once, shown again) against the golden-image tolerance (at most 0.5 %% of the pixels "
                      "over 8/255): along the camera path the view turns %.2f px a tick at the image centre (median of %zu ticks; %.0f %% "
                      "of the ticks turn 0.1 px or more, %.0f %% 0.5 px or more). The default pass drawn again with the view moved by a "
                      "fraction of a pixel, against its image before (kept) or shifted bilinearly to follow, over the cameras:\n\n",
                      turns[turns.size() / 2], turns.size(), turnedAtLeast(0.1), turnedAtLeast(0.5));
        t << line;
        bench::ResultTable reuse({{"", "view moved by", "%.2f px"}, {"", "pixels over 8/255, kept (mean, worst)", "%s"}, {"", "PSNR dB kept (worst)", "%.1f"},
                                  {"", "pixels over 8/255, shifted (mean, worst)", "%s"}, {"", "PSNR dB shifted (worst)", "%.1f"}});
        const auto meanAndWorst = [&](const std::vector<double>& v) {
            char cell[64];
            std::snprintf(cell, sizeof cell, "%.2f %%, %.2f %%", 100.0 * mean(v), 100.0 * *std::max_element(v.begin(), v.end()));
            return std::string(cell);
        };
        for (std::size_t i = 0; i < r.reuse.size(); ++i) {
            const ImageReuse& u = r.reuse[i];
            reuse.add({kReuseOffsets[i], meanAndWorst(u.keptOver), *std::min_element(u.keptPsnr.begin(), u.keptPsnr.end()),
                       meanAndWorst(u.shiftedOver), *std::min_element(u.shiftedPsnr.begin(), u.shiftedPsnr.end())});
        }
        t << reuse.markdown();
    }
    if (!r.lodDeclared) t << "\nThe scene declares no town LOD; the LOD rows use 50 m full, 100 m half the triangles, a quarter beyond.\n";
    std::vector<bench::ResultTable::Column> columns{{"", "time", "%.1f"}};
    for (const TownVariant& v : r.variants) columns.push_back({"", v.name, "%.1f"});
    bench::ResultTable perCamera(columns);
    for (std::size_t i = 0; i < r.times.size(); ++i) {
        std::vector<bench::ResultTable::Cell> row{r.times[i]};
        for (const TownVariant& v : r.variants) row.push_back(v.ms[i]);
        perCamera.add(std::move(row));
    }
    t << "\nPer camera (path time in s), ms:\n\n" << perCamera.markdown();
    return t.str();
}

// The method rows: the CSV (its columns as scripts read them) and the Markdown table (fps added,
// hidden before triangles).
bench::ResultTable methodTable(const std::vector<Row>& rows) {
    bench::ResultTable t({{"actors", "actors", "%lld"}, {"camera", "camera", "%s", true}, {"method", "method", "%s", true},
                          {"step_ms", "step", "%.2f"}, {"app_ms", "APP", "%.2f"}, {"", "occlusion buffer", "%.2f"}, {"cull1_ms", "CULL 1", "%.2f"},
                          {"roots_ms", "roots", "%.2f"}, {"cull2_ms", "CULL 2", "%.2f"}, {"pose_ms", "poses", "%.2f"}, {"cull3_ms", "CULL 3", "%.2f"},
                          {"list_ms", "list", "%.2f"}, {"app_cull_ms", "APP+CULL", "%.2f"}, {"impostor_batch_ms", "impostor batch", "%.2f"},
                          {"morph_ms", "morph", "%.2f"}, {"town_ms", "town draw", "%.1f"}, {"mesh_ms", "mesh draw", "%.1f"},
                          {"impostor_draw_ms", "impostor draw", "%.1f"}, {"finish_ms", "finish", "%.1f"}, {"draw_ms", "DRAW", "%.1f"},
                          {"frame_ms", "whole frame", "%.1f"}, {"", "fps", "%.1f"}, {"posed", "posed", "%.0f"}, {"impostors", "impostors", "%.0f"},
                          {"draw_items", ""}, {"triangles", ""}, {"occlusion_buffer_ms", ""}, {"hidden", "hidden", "%.0f"}, {"", "triangles", "%.0f"}});
    for (const Row& r : rows)
        t.add({r.actors, r.camera, r.method, r.step, r.app, r.occlusionBuffer, r.cull1, r.roots, r.cull2, r.pose, r.cull3, r.list, r.appCull, r.batch,
               r.morph, r.town, r.meshes, r.quads, r.finish, r.draw, r.frame, 1000.0 / r.frame, r.posed, r.impostors, r.items, r.triangles,
               r.occlusionBuffer, r.hidden, r.triangles});
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    bench::Experiment experiment("bench_frame",
                                 "The whole frame of the town crowd: traditional, actor, actor + impostor processing, each of the\n"
                                 "last two with occlusion culling, on the identical state, side by side; then APP+CULL with 1\n"
                                 "and 2 threads, the pipelined frame, and (when asked) the occlusion buffer's resolution.",
                                 bench::kScene | bench::kActorList | bench::kCameras | bench::kFrames | bench::kWarmup | bench::kImageSize |
                                     bench::kCsv | bench::kMarkdown,
                                 {.scene = testkit::townDefaultScene(), .actors = {2000, 6000, 10000}, .cameras = {"street", "overview"},
                                  .frames = 30, .warmup = 60},
                                 {.csvHelp = "also write the method rows as CSV"});
    CLI::App& app = experiment.app();
    app.add_option("--scaling-actors", o.scalingActors, "actors of the 1-versus-2-threads section (0: skip)")
        ->type_name("N")->check(CLI::Range(0, 10'000'000));
    app.add_option("--scaling-frames", o.scalingFrames, "measured ticks of that section")->type_name("N")->check(CLI::Range(1, 1'000'000));
    app.add_option("--pipeline-actors", o.pipelineActors, "actors of the pipeline section (0: the scene's own)")
        ->type_name("N")->check(CLI::Range(0, 10'000'000));
    app.add_option("--pipeline-frames", o.pipelineFrames, "frames of each pipeline run (0: skip)")
        ->type_name("N")->check(CLI::Range(0, 1'000'000));
    app.add_option("--sections", o.sections,
                   "what to run: methods (all methods side by side), scaling (1 and 2 threads), pipeline; not run unless "
                   "named: town (the town's DRAW alone, old and new drawing), occlusion (buffer resolution against rejection and time), "
                   "visibility (what a perfect occlusion culler could reach, from an ID render with full depth), regions (the shared step "
                   "of large crowds, one region against the scene's, 1 and 2 threads)")
        ->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("NAME,...")->check(CLI::IsMember({"methods", "scaling", "pipeline", "town", "occlusion", "visibility", "regions"}));
    app.add_option("--region-actors", o.regionActors, "crowds of the regions section (the shared step, one region against the scene's)")
        ->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("N,N,...")->check(CLI::Range(1, 10'000'000));
    app.add_option("--region-frames", o.regionFrames, "measured steps per thread count in the regions section")
        ->type_name("N")->check(CLI::Range(2, 1'000'000));
    app.add_option("--occlusion-actors", o.occlusionActors, "actors of the occlusion section")
        ->type_name("N")->check(CLI::Range(1, 10'000'000));
    app.add_option("--occlusion-rests", o.occlusionRests, "rest lengths of the occlusion section's resting rows (default: the scene's)")
        ->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("N,N,...")->check(CLI::Range(1, 1000));
    app.add_flag("--occlusion-path", o.occlusionPath, "the occlusion section also follows the scene's camera path once, tick by tick");
    app.add_option("--occlusion-csv", o.occlusionCsv, "also write the occlusion section in the common accuracy CSV (one record per buffer resolution and camera)")->type_name("FILE")->check(bench::fileToWrite());
    experiment.markOutput("--occlusion-csv");
    app.add_option("--town-actors", o.townActors, "actors of the town section")->type_name("N")->check(CLI::Range(1, 10'000'000));
    app.add_option("--town-samples", o.townSamples, "cameras along the path in the town section")
        ->type_name("N")->check(CLI::Range(1, 10'000));
    app.add_option("--town-frames", o.townFrames, "frames per camera and variant in the town section")
        ->type_name("N")->check(CLI::Range(1, 10'000));
    if (const auto code = experiment.parse(argc, argv)) return *code;
    o.e = experiment.spec();

    std::ostringstream report;
    try {
        auto context = bench::experimentContext(o.e);
        std::vector<Row> rows;
        std::uint64_t ticks = 0;
        for (std::int64_t n : o.has("methods") ? o.e.actors : std::vector<std::int64_t>{}) {
            std::fprintf(stderr, "bench_frame: %lld actors: building, baking impostors, %d ticks per camera...\n", (long long)n,
                         o.e.frames);
            const auto part = compareMethods(o, n, context, &ticks);
            rows.insert(rows.end(), part.begin(), part.end());
        }
        if (o.has("methods")) {
            report << "Identical state: every method saw the same state digest on each of " << ticks << " ticks.\n\n";
            report << "Milliseconds per frame, " << o.e.width << " x " << o.e.height << " headless, " << context->description()
                   << ", one thread; means over " << o.e.frames << " ticks (`" << experiment.reproduction() << "`).\n\n"
                   << methodTable(rows).markdown();
        }
        if (!o.e.csv.empty()) bench::writeWhole(o.e.csv, methodTable(rows).csv());
        if (o.has("scaling") && o.scalingActors > 0) {
            std::fprintf(stderr, "bench_frame: %lld actors with 1 and 2 threads...\n", (long long)o.scalingActors);
            const auto scaling = threadScaling(o);
            report << "\nAPP+CULL and the step with 1 and 2 threads, " << o.scalingActors
                   << " actors, two worlds of the same seed (identical digests on every tick):\n\n";
            bench::ResultTable t({{"", "camera", "%s", true}, {"", "step 1 / 2 threads", "%s"}, {"", "speed-up", "%.2f"},
                                  {"", "actor 1 / 2 threads", "%s"}, {"", "speed-up", "%.2f"}, {"", "traditional 1 / 2 threads", "%s"},
                                  {"", "speed-up", "%.2f"}});
            const auto pair = [](const double (&v)[2]) {
                char cell[64];
                std::snprintf(cell, sizeof cell, "%.2f / %.2f", v[0], v[1]);
                return std::string(cell);
            };
            for (const Scaling& s : scaling)
                t.add({s.camera, pair(s.step), s.step[0] / s.step[1], pair(s.actor), s.actor[0] / s.actor[1], pair(s.traditional),
                       s.traditional[0] / s.traditional[1]});
            report << t.markdown();
        }
        if (o.has("regions")) {
            const double before = availableSpeedup();
            const auto regionRows = regionSweep(o);
            const double after = availableSpeedup();
            report << "\nThe shared step (walkers, idle groups, gaze, flock) of large crowds, the town grown at the scene's density, "
                   << "milliseconds per step, means over " << o.regionFrames << " steps per thread count after " << o.e.warmup
                   << " (ghosts and handovers per step; peak memory of the process so far). A loop with nothing shared ran "
                   << std::fixed << std::setprecision(2) << before << "x and " << after << "x as fast on 2 threads as on 1 before and "
                   << "after the section: the most the machine, shared with other work, could give.\n\n" << std::defaultfloat;
            bench::ResultTable t({{"", "actors", "%lld"}, {"", "layout", "%s", true}, {"", "regions", "%s"}, {"", "step 1 thread", "%s"},
                                  {"", "step 2 threads", "%s"}, {"", "speed-up", "%s"}, {"", "ghosts", "%s"}, {"", "handovers", "%s"},
                                  {"", "build s", "%s"}, {"", "peak GB", "%s"}});
            const auto fixed = [](const char* format, double v) {
                char cell[64];
                std::snprintf(cell, sizeof cell, format, v);
                return std::string(cell);
            };
            for (const RegionRow& r : regionRows) {
                if (!r.note.empty()) t.add({r.actors, r.layout, "", r.note, "", "", "", "", "", ""});
                else
                    t.add({r.actors, r.layout, std::to_string(r.regions), fixed("%.2f", r.ms[0]), fixed("%.2f", r.ms[1]), fixed("%.2f", r.ms[0] / r.ms[1]),
                           fixed("%.0f", r.ghosts), fixed("%.1f", r.handovers), fixed("%.1f", r.buildSeconds), fixed("%.2f", r.peakGb)});
            }
            report << t.markdown();
        }
        if (o.has("pipeline") && o.pipelineFrames > 0) {
            std::fprintf(stderr, "bench_frame: the pipelined frame, %d frames each way...\n", o.pipelineFrames);
            const PipelineResult p = pipelineFps(o, context);
            char line[512];
            std::snprintf(line, sizeof line,
                          "\nEnd to end (step, APP/CULL, DRAW with impostors, the street camera following the path), %lld actors: "
                          "%.1f fps with DRAW overlapping the next frame, %.1f fps without (%.2fx).\n",
                          (long long)p.actors, p.fps[1], p.fps[0], p.fps[1] / p.fps[0]);
            report << line;
        }
        if (o.has("occlusion")) {
            std::fprintf(stderr, "bench_frame: occlusion buffer resolutions, %lld actors...\n", (long long)o.occlusionActors);
            std::int64_t actors = 0;
            const auto sweep = occlusionSweep(o, context, &actors);
            report << "\nOcclusion buffer resolution against rejection and time, actor + impostors processing, " << actors
                   << " actors, one thread, means over " << o.e.frames << " ticks (\"hidden\": actors rejected by occlusion, as a share of those "
                   << "reaching CULL 1; the rejection is conservative at every resolution: lower ones only reject less"
                   << "; \"rested\": share of frames the stage rested after one that hid little; the path camera follows the "
                   << "scene's camera path once, means over its ticks):\n\n";
            bench::ResultTable table({{"", "camera", "%s", true}, {"", "buffer", "%s", true}, {"", "buffer ms", "%.3f"}, {"", "APP+CULL ms", "%.2f"},
                                      {"", "hidden", "%.0f"}, {"", "hidden share", "%.1f %%"}, {"", "posed", "%.0f"}, {"", "tiles hidden", "%.0f"},
                                      {"", "rested", "%.0f %%"}});
            // The common accuracy CSV. Occlusion is conservative (no visible actor is rejected at any
            // resolution), so its measures are what it achieves: the share hidden, and the posing left.
            std::unique_ptr<sim::AccuracyCsv> csv;
            if (!o.occlusionCsv.empty()) csv = std::make_unique<sim::AccuracyCsv>(o.occlusionCsv);
            const auto record = [&](const OcclusionRow& row, const char* knob, const std::string& value, bool off) {
                sim::AccuracyRecord a;
                a.knob = knob;
                a.value = value;
                a.off = off;
                a.metrics = {{"hidden_share", row.hiddenShare(), "share", false}, {"actors_posed", row.posed, "actors", true},
                             {"tiles_hidden", row.tiles, "tiles", false}};
                a.ms = row.appCullMs;
                a.msPhase = "app_cull";
                // A buffer and its pyramid: four bytes a pixel, a third more for the coarser levels.
                a.memoryBytes = double(std::int64_t(row.width) * row.height * 16 / 3);
                a.scene = sim::sceneName(o.e.scene);
                a.camera = row.camera;
                a.actors = actors;
                csv->add(a);
            };
            for (const OcclusionRow& r : sweep) {
                const std::string size = r.label();
                table.add({r.camera, size, r.bufferMs, r.appCullMs, r.hidden, 100.0 * r.hiddenShare(), r.posed, r.tiles, 100.0 * r.rested});
                if (csv && !r.rest) record(r, "occlusion buffer resolution", size, r.width == 0);
                // Knob "occlusion rest": its "off" is the same resolution testing every frame.
                if (csv && r.rest) {
                    for (const OcclusionRow& every : sweep)
                        if (every.camera == r.camera && every.width == r.width && every.height == r.height && every.rest == 0)
                            record(every, "occlusion rest", "every frame", true);
                    record(r, "occlusion rest", std::to_string(r.rest) + " frames", false);
                }
            }
            report << table.markdown();
        }
        if (o.has("visibility")) {
            std::fprintf(stderr, "bench_frame: the visibility bound, %lld actors...\n", (long long)o.occlusionActors);
            std::int64_t actors = 0;
            const auto bound = visibilityBound(o, context, &actors);
            report << "\nWhat occlusion culling could reach, " << actors << " actors, " << o.e.width << "x" << o.e.height
                   << " (an ID render with full depth: actors with a visible pixel; a conservative culler keeps them all):\n\n";
            bench::ResultTable t({{"", "camera", "%s", true}, {"", "processing", "%s", true}, {"", "drawn as meshes without occlusion", "%lld"},
                                  {"", "of those with a visible pixel", "%lld"}, {"", "best possible reduction", "%.2fx"},
                                  {"", "visible past the town alone", "%lld"}, {"", "best with the town as the only occluder", "%.2fx"},
                                  {"", "drawn as meshes with occlusion", "%lld"}, {"", "reduction reached", "%.2fx"}});
            const auto ratio = [](std::size_t a, std::size_t b) { return double(a) / double(std::max<std::size_t>(b, 1)); };
            for (const VisibilityRow& r : bound)
                t.add({r.camera, r.method, std::int64_t(r.meshActors), std::int64_t(r.visible), ratio(r.meshActors, r.visible),
                       std::int64_t(r.visibleTown), ratio(r.meshActors, r.visibleTown), std::int64_t(r.withOcclusion),
                       ratio(r.meshActors, r.withOcclusion)});
            report << t.markdown();
        }
        if (o.has("town")) {
            std::fprintf(stderr, "bench_frame: the town's DRAW, %d cameras along the path...\n", o.townSamples);
            const TownResult town = townDraw(o, context);
            report << (report.tellp() > 0 ? "\n" : "") << townTable(town, o, context->description());
        }
        std::fputs(report.str().c_str(), stdout);
        if (!o.e.markdown.empty()) bench::writeWhole(o.e.markdown, report.str());
    } catch (const std::exception& e) {
        fail(e.what());
    }
    return 0;
}
