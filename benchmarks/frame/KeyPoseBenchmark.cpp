// bench_keypose: seed 004's key-pose cache on the town crowd, every setting on the identical state.
//
// Each tick the simulation steps once, outside every processor; then plain skinning (the scene's
// own representation: skinned near, impostors far, occlusion as declared) and the intermittent and
// interpolative caches at each size (the same, with the middle band drawn from the caches) each run
// APP and CULL on that state and DRAW their own list, the GL finished after each pass. Every method
// must see the same state digest. Figures in the style of seed 004:
//   - Fig. 9: frame time (APP+CULL, mesh draw, whole frame) against cache size, each mode beside
//     plain skinning;
//   - Fig. 11: share of the band's actors the cache serves, frame by frame along the camera path;
//   - Fig. 7 on recorded frames: `--demands FILE` writes what the band needed each frame, for
//     bench_keypose_selection (greedy against the exact selection).
// Accuracy: the vertex error (mean and maximum, millimetres, world space) of the cached actors
// against the same actors skinned by plain skinning, and the image error of the whole frame against
// plain skinning's (PSNR, SSIM, share of pixels off by more than 8/255), written in the common
// accuracy CSV (`--accuracy-csv`).
//
// usage: bench_keypose --help

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "throng/bench/Experiment.h"
#include "throng/bench/FrameWorld.h"
#include "throng/bench/ResultTable.h"
#include "throng/bench/SameState.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CpuSkinning.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/testkit/ImageSimilarity.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/AccuracyCsv.h"
#include "throng/testkit/Assets.h"
#include "throng/vtk/Chart.h"

using namespace throng;

namespace {

[[noreturn]] void fail(const std::string& why) { bench::fail("bench_keypose", why); }

// The experiment's settings: the common ones (e) and its own.
struct Options {
    bench::ExperimentSpec e;    // scene, actor counts, cameras, measured ticks per camera, warmup, size, outputs
    std::vector<std::int64_t> sizes{8, 16, 32, 64, 128, 256};
    int errorSamples = 48;      // cached actors compared per method and measured tick
    int pathFrames = 90;        // frames along the camera path for Fig. 11 (0: skip)
    double distance = 0;        // start of the band (0: the scene's declaration, else 15 m)
    double rate = 0;            // key-poses per second (0: the scene's declaration, else 15)
    std::int64_t demandSize = 32;  // cache size whose interpolative demands --demands records
    std::string demands;
};

// One setting: plain skinning (size 0) or a cache mode and size.
struct Method {
    std::string name;
    KeyPoseMode mode = KeyPoseMode::Intermittent;
    std::uint32_t size = 0;
    std::unique_ptr<ActorProcessor> processor;
};

// Means over the measured ticks of one method on one camera.
struct Row {
    std::int64_t actors = 0;
    std::string camera, method;
    std::uint32_t size = 0;
    double appCull = 0, pose = 0, select = 0, mesh = 0, draw = 0, frame = 0;
    double band = 0, served = 0, misses = 0, updates = 0, fills = 0, posed = 0, cacheBytes = 0;
    double vertexSum = 0, vertexCount = 0, vertexMax = 0;  // metres, against plain skinning
    double keySum = 0, keyMax = 0;                          // metres, against the clip at the actor's own time
    double psnr = 0, ssim = 0, off8 = 0, images = 0;
    void add(const ActorFrameStatistics& s, const CrowdRenderStatistics& r, double stepMs, double drawMs) {
        appCull += s.appCullMs();
        pose += s.poseMs;
        select += s.keyPoseSelectMs;
        mesh += r.meshMs;
        draw += drawMs;
        frame += stepMs + s.appCullMs() + drawMs;
        band += double(s.keyPoseBand);
        served += double(s.keyPoseActors);
        misses += double(s.keyPoseMisses);
        updates += double(s.keyPoseUpdates);
        fills += double(r.meshes.keyPoseFills);
        posed += double(s.actorsPosed);
        cacheBytes = std::max(cacheBytes, double(r.meshes.keyPoseCacheBytes));
    }
    void divide(double n) {
        for (double* v : {&appCull, &pose, &select, &mesh, &draw, &frame, &band, &served, &misses, &updates, &fills, &posed}) *v /= n;
        if (images > 0) psnr /= images, ssim /= images, off8 /= images;
    }
    double vertexMeanMm() const { return vertexCount > 0 ? 1000.0 * vertexSum / vertexCount : 0.0; }
    double keyMeanMm() const { return vertexCount > 0 ? 1000.0 * keySum / vertexCount : 0.0; }
};

// Caches for every template in use that can have one (skinned, no rigid parts), `size` rows each.
void attachCaches(ActorProcessor& p, const sim::Simulation& world, KeyPoseMode mode, std::uint32_t size, double rate) {
    for (const auto& t : world.templates()) {
        KeyPoseCacheSettings s;
        s.rows = size;
        s.mode = mode;
        s.keyPosesPerSecond = rate;
        try {
            p.setKeyPoseCache(std::make_shared<KeyPoseCache>(t.tmpl, s));
        } catch (const std::invalid_argument&) {
            // A template drawn by rigid parts (the birds): no cache, as in a scene file.
        }
    }
}

// Vertices of `item`'s mesh skinned with `palette` and placed in the world (its world matrix).
void worldVertices(const DrawItem& item, std::span<const glm::mat4> palette, std::vector<glm::vec3>& out) {
    const MeshData& mesh = static_cast<const MeshDrawable*>(item.drawable)->mesh();
    std::vector<glm::vec3> local(mesh.vertexCount());
    skinMesh(mesh, palette, local, {});
    out.resize(local.size());
    for (std::size_t i = 0; i < local.size(); ++i) out[i] = glm::vec3(item.world.toMat4() * Vec4(Vec3(local[i]), 1.0));
}

// The palette of skin `skin` of `tmpl` playing `clip` at `clipTime` at full detail: what the
// key-pose cache approximates when it snaps (intermittent) or blends (interpolative) key-poses.
std::vector<glm::mat4> clipPalette(const ActorTemplate& tmpl, int clip, double clipTime, std::uint32_t skin) {
    std::vector<float> dofs(tmpl.restDofs().begin(), tmpl.restDofs().end());
    tmpl.clips()[std::size_t(clip)]->sample(tmpl, clipTime, true, {}, dofs);
    std::vector<Affine> model(tmpl.nodeCount());
    computeModelTransforms(tmpl, dofs, {}, model);
    std::vector<glm::mat4> palette(tmpl.skins()[skin].joints.size());
    computeSkinPalette(tmpl, tmpl.skins()[skin], model, {}, palette);
    return palette;
}

// Vertex error of up to `samples` cached actors of `list` against the same actors in `plain` (what
// the user sees change: the key-pose and everything the cache leaves out, a turned head, a blend
// into running) and against their own clip at their own time (the key-pose alone).
void vertexError(const DrawList& list, const DrawList& plain, int samples, Row& row) {
    std::vector<const DrawItem*> skinned;
    for (const DrawItem& item : plain.items())
        if (item.actor != kNoActor && item.skinPalette) {
            if (skinned.size() <= item.actor) skinned.resize(item.actor + 1, nullptr);
            skinned[item.actor] = &item;
        }
    std::vector<const DrawItem*> cached;
    for (const DrawItem& item : list.items())
        if (item.representation == Representation::KeyPose && item.actor < skinned.size() && skinned[item.actor]) cached.push_back(&item);
    const std::size_t stride = std::max<std::size_t>(1, cached.size() / std::size_t(std::max(samples, 1)));
    std::vector<glm::vec3> exact, a, b, clipExact;
    for (std::size_t k = 0; k < cached.size(); k += stride) {
        const DrawItem& item = *cached[k];
        const DrawItem& truth = *skinned[item.actor];
        if (truth.drawable != item.drawable) continue;  // another vaLod level: not comparable vertex by vertex
        const KeyPoseRef& ref = item.keyPose;
        worldVertices(truth, {truth.skinPalette, truth.skinPaletteSize}, exact);
        worldVertices(item, ref.source->palette(ref.skin, ref.pose[0]), a);
        if (ref.blend > 0.0f) worldVertices(item, ref.source->palette(ref.skin, ref.pose[1]), b);
        const auto& cache = dynamic_cast<const KeyPoseCache&>(*ref.source);
        worldVertices(item, clipPalette(cache.actorTemplate(), item.clip, item.clipTime, ref.skin), clipExact);
        for (std::size_t v = 0; v < exact.size(); ++v) {
            const glm::vec3 shown = ref.blend > 0.0f ? a[v] * (1.0f - ref.blend) + b[v] * ref.blend : a[v];
            const double e = glm::length(shown - exact[v]);
            const double q = glm::length(shown - clipExact[v]);
            row.vertexSum += e;
            row.keySum += q;
            row.vertexCount += 1;
            row.vertexMax = std::max(row.vertexMax, e);
            row.keyMax = std::max(row.keyMax, q);
        }
    }
}

struct Result {
    std::vector<Row> rows;
    std::vector<double> pathTimes;                 // Fig. 11: camera path times
    std::vector<std::vector<double>> pathServed;   // per cache method: served share of the band per frame (NaN: empty band)
    std::vector<std::string> pathMethods;
    std::uint64_t ticks = 0;
};

// Runs every method on `actors` actors; with `demandsOut`, writes the demands of the camera path,
// numbering instances from *instance on.
Result run(const Options& o, std::int64_t actors, const std::shared_ptr<GlContext>& context, std::ofstream* demandsOut,
           std::uint64_t* instance) {
    auto world = bench::buildWorld(o.e.scene, actors);
    auto impostors = bench::bakeImpostors(context, *world);
    context->resize(o.e.width, o.e.height);
    const auto& declared = world->description().representation.keyPoseCache;
    const double distance = o.distance > 0 ? o.distance : declared ? declared->distance : 15.0;
    const double rate = o.rate > 0 ? o.rate : declared ? declared->keyPosesPerSecond : 15.0;
    const double hysteresis = world->description().representation.hysteresis * distance;
    const auto [impostorDistance, impostorHysteresis] = bench::impostorDistance(*world);
    std::vector<Method> methods;
    methods.push_back({"plain skinning", KeyPoseMode::Intermittent, 0, nullptr});
    for (KeyPoseMode mode : {KeyPoseMode::Intermittent, KeyPoseMode::Interpolative})
        for (std::int64_t size : o.sizes)
            methods.push_back({std::string(mode == KeyPoseMode::Intermittent ? "intermittent " : "interpolative ") + std::to_string(size),
                               mode, std::uint32_t(size), nullptr});
    for (Method& m : methods) {
        m.processor = std::make_unique<ActorProcessor>(world->crowd());
        impostors->attach(*m.processor, impostorDistance, impostorHysteresis);
        if (world->description().representation.occlusion) m.processor->setOcclusion(world->description().representation.occlusion);
        if (m.size == 0) continue;
        attachCaches(*m.processor, *world, m.mode, m.size, rate);
        m.processor->setKeyPoseDistance(distance, hysteresis);
    }
    // One renderer per method: each keeps its own morph cache and key-pose rows, as throng-town's
    // one renderer would, so no method draws on what another method's frame left behind.
    CrowdRendererOptions ro;
    ro.finishPasses = true;
    std::vector<std::unique_ptr<CrowdRenderer>> renderers;
    for (std::size_t m = 0; m < methods.size(); ++m) renderers.push_back(std::make_unique<CrowdRenderer>(context, ro));
    for (int f = 0; f < o.e.warmup; ++f) world->step();
    Result result;
    const double aspect = double(o.e.width) / double(o.e.height);
    std::vector<Image> frames(methods.size());
    for (const std::string& cameraName : o.e.cameras) {
        const Camera camera = world->camera().at(bench::cameraTime(cameraName), aspect);
        std::vector<Row> rows(methods.size());
        for (std::size_t m = 0; m < methods.size(); ++m) {
            rows[m].actors = std::int64_t(world->crowd().size());
            rows[m].camera = cameraName;
            rows[m].method = methods[m].name;
            rows[m].size = methods[m].size;
        }
        for (int f = -2; f < o.e.frames; ++f) {  // two unmeasured ticks fill the caches and warm the GL
            const FrameContext& now = world->step();
            const double stepMs = world->lastStepMs();
            const bool measureError = f >= 0 && f % o.e.errorEvery == 0;
            bench::runOnSameState(world->crowd(), methods.size(), f + 2, [&](std::size_t m) {
                ActorProcessor& p = *methods[m].processor;
                const ActorFrameStatistics s = p.processFrame(world->root(), camera, now.time);
                CrowdRenderer& renderer = *renderers[m];
                Stopwatch watch;
                renderer.drawFrame(camera, p.drawList());
                const double drawMs = watch.elapsedMs();
                if (f < 0) return;
                rows[m].add(s, renderer.statistics(), stepMs, drawMs);
                if (measureError) frames[m] = renderer.readFrame();
            }, [&](std::size_t m) { return methods[m].name; });
            if (f >= 0) ++result.ticks;
            if (!measureError) continue;
            for (std::size_t m = 1; m < methods.size(); ++m) {
                vertexError(methods[m].processor->drawList(), methods[0].processor->drawList(), o.errorSamples, rows[m]);
                bench::addFrameError(frames[m], frames[0], rows[m].psnr, rows[m].ssim, rows[m].off8);
                rows[m].images += 1;
            }
        }
        for (Row& r : rows) {
            r.divide(o.e.frames);
            result.rows.push_back(r);
        }
        std::fprintf(stderr, "bench_keypose: %lld actors, %s camera done\n", (long long)actors, cameraName.c_str());
    }
    // Fig. 11: the camera follows its path; served share of the band for every cache method.
    if (o.pathFrames > 0) {
        for (std::size_t m = 1; m < methods.size(); ++m) result.pathMethods.push_back(methods[m].name);
        result.pathServed.resize(methods.size() - 1);
        const double duration = world->camera().duration();
        for (int f = 0; f < o.pathFrames; ++f) {
            const double t = duration * f / std::max(o.pathFrames - 1, 1);
            const Camera camera = world->camera().at(t, aspect);
            const FrameContext& now = world->step();
            result.pathTimes.push_back(t);
            for (std::size_t m = 1; m < methods.size(); ++m) {
                const ActorFrameStatistics& s = methods[m].processor->processFrame(world->root(), camera, now.time);
                result.pathServed[m - 1].push_back(s.keyPoseBand ? double(s.keyPoseActors) / double(s.keyPoseBand)
                                                                 : std::numeric_limits<double>::quiet_NaN());
                // One selection instance per tick and template (bench_keypose_selection's "frame").
                if (demandsOut && methods[m].mode == KeyPoseMode::Interpolative && methods[m].size == std::uint32_t(o.demandSize))
                    for (const auto& cache : methods[m].processor->keyPoseCaches()) {
                        if (cache->lastDemand().empty()) continue;
                        for (const KeyPoseDemand& d : cache->lastDemand())
                            *demandsOut << *instance << ',' << d.a << ',' << d.b << ',' << d.actors << '\n';
                        ++*instance;
                    }
            }
        }
        std::fprintf(stderr, "bench_keypose: %lld actors, camera path done\n", (long long)actors);
    }
    return result;
}

// The rows: the CSV has every figure in a column of its own, the Markdown pairs mean and maximum.
bench::ResultTable table(const std::vector<Row>& rows) {
    bench::ResultTable t({{"actors", "actors", "%lld"},
                          {"camera", "camera", "%s", true},
                          {"method", "method", "%s", true},
                          {"size", "", "%lld"},
                          {"app_cull_ms", "APP+CULL", "%.2f"},
                          {"pose_ms", "poses", "%.2f"},
                          {"select_ms", "selection", "%.3f"},
                          {"mesh_ms", "mesh draw", "%.1f"},
                          {"draw_ms", "DRAW", "%.1f"},
                          {"frame_ms", "whole frame", "%.1f"},
                          {"band", "band", "%.0f"},
                          {"served", "from cache", "%.0f"},
                          {"misses", "skinned in band", "%.0f"},
                          {"updates", "cache updates", "%.1f"},
                          {"fills", "rows skinned (DRAW)", "%.1f"},
                          {"posed", "posed", "%.0f"},
                          {"vertex_error_mean_mm", "", "%g"},
                          {"vertex_error_max_mm", "", "%g"},
                          {"", "vertex error mean / max mm", "%s"},
                          {"key_pose_error_mean_mm", "", "%g"},
                          {"key_pose_error_max_mm", "", "%g"},
                          {"", "key-pose error mean / max mm", "%s"},
                          {"psnr_db", "", "%g"},
                          {"", "PSNR dB", "%s"},
                          {"ssim", "", "%g"},
                          {"", "SSIM", "%s"},
                          {"pixels_off_8", "", "%g"},
                          {"", "pixels off > 8", "%s"}});
    char pair[64];
    const auto both = [&](double mean, double max) {
        std::snprintf(pair, sizeof pair, "%.1f / %.0f", mean, max);
        return std::string(pair);
    };
    for (const Row& r : rows)
        t.add({r.actors, r.camera, r.method, std::int64_t(r.size), r.appCull, r.pose, r.select, r.mesh, r.draw, r.frame, r.band, r.served, r.misses,
               r.updates, r.fills, r.posed, r.vertexMeanMm(), 1000.0 * r.vertexMax, both(r.vertexMeanMm(), 1000.0 * r.vertexMax), r.keyMeanMm(),
               1000.0 * r.keyMax, both(r.keyMeanMm(), 1000.0 * r.keyMax), r.psnr, r.images ? std::to_string(r.psnr).substr(0, 5) : "-", r.ssim,
               r.images ? std::to_string(r.ssim).substr(0, 6) : "-", r.off8, r.images ? std::to_string(100.0 * r.off8).substr(0, 5) + " %" : "-"});
    return t;
}

// Writes `chart` without its empty series (a camera that saw no actor in the band has none), and
// nothing when no series is left; a chart that cannot be written is reported, not fatal.
void writeChart(vtk::Chart chart, const std::string& path) {
    std::erase_if(chart.series, [](const vtk::ChartSeries& s) { return s.x.empty(); });
    if (chart.series.empty()) {
        std::fprintf(stderr, "bench_keypose: no data for '%s', not drawn\n", chart.title.c_str());
        return;
    }
    try {
        vtk::writeChartPng(chart, path);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_keypose: %s\n", e.what());
    }
}

// The figures as PNG (VTK charts need a display: under xvfb-run).
void plots(const Options& o, const std::vector<Result>& results) {
    namespace fs = std::filesystem;
    fs::create_directories(o.e.plots);
    for (const Result& res : results) {
        if (res.rows.empty()) continue;
        const std::string tag = std::to_string(res.rows.front().actors);
        for (const std::string& cameraName : o.e.cameras) {
            // Fig. 9: the whole frame and the mesh pass on one chart, APP+CULL (ten times smaller) on its own.
            const char* names[] = {"intermittent", "interpolative"};
            const auto timeChart = [&](const std::string& title, std::initializer_list<const char*> whats, const std::string& file) {
                vtk::Chart chart;
                chart.title = title + ", " + tag + " actors, " + cameraName + " camera";
                chart.xLabel = "cache size (key-poses per template)";
                chart.yLabel = "ms per frame";
                chart.logX = true;
                chart.legend = vtk::Chart::Legend::Bottom;
                int colour = 0;
                for (const char* what : whats) {
                    for (int mode = 0; mode < 3; ++mode) {
                        vtk::ChartSeries s;
                        s.name = std::string(mode == 0 ? "plain skinning" : names[mode - 1]) + ": " + what;
                        for (const Row& r : res.rows) {
                            if (r.camera != cameraName) continue;
                            const std::string w = what;
                            const double v = w == "whole frame" ? r.frame : w == "APP+CULL" ? r.appCull : r.mesh;
                            if (mode == 0 && r.size == 0) {
                                for (std::int64_t size : o.sizes) s.x.push_back(double(size)), s.y.push_back(v);
                            } else if (mode > 0 && r.size > 0 && r.method.rfind(names[mode - 1], 0) == 0) {
                                s.x.push_back(double(r.size));
                                s.y.push_back(v);
                            }
                        }
                        s.style = mode == 0 ? vtk::ChartSeries::Style::DashedLine : vtk::ChartSeries::Style::LineAndPoints;
                        vtk::paletteColour(colour++, s.rgb);
                        chart.series.push_back(s);
                    }
                }
                writeChart(chart, (fs::path(o.e.plots) / (file + "-" + tag + "-" + cameraName + ".png")).string());
            };
            timeChart("Frame time against cache size (seed 004 Fig. 9)", {"whole frame", "mesh draw"}, "keypose-frame-time");
            timeChart("APP+CULL against cache size", {"APP+CULL"}, "keypose-app-cull");
            vtk::Chart served;
            served.title = "Actors of the band drawn from the cache, " + tag + " actors, " + cameraName + " camera";
            served.xLabel = "cache size (key-poses per template)";
            served.yLabel = "share of the band";
            served.logX = true;
            for (int mode = 0; mode < 2; ++mode) {
                vtk::ChartSeries s;
                s.name = names[mode];
                for (const Row& r : res.rows)
                    if (r.camera == cameraName && r.size > 0 && r.method.rfind(names[mode], 0) == 0 && r.band > 0)
                        s.x.push_back(double(r.size)), s.y.push_back(r.served / r.band);
                s.style = vtk::ChartSeries::Style::LineAndPoints;
                vtk::paletteColour(mode, s.rgb);
                served.series.push_back(s);
            }
            writeChart(served, (fs::path(o.e.plots) / ("keypose-served-" + tag + "-" + cameraName + ".png")).string());
        }
        if (res.pathTimes.empty()) continue;
        vtk::Chart path;
        path.title = "Share of the band drawn from the cache along the camera path, " + tag + " actors (seed 004 Fig. 11)";
        path.xLabel = "camera path time (s)";
        path.yLabel = "share of the band";
        path.legend = vtk::Chart::Legend::Bottom;
        for (std::size_t m = 0; m < res.pathMethods.size(); ++m) {
            vtk::ChartSeries s;
            s.name = res.pathMethods[m];
            for (std::size_t f = 0; f < res.pathTimes.size(); ++f)  // frames with nobody in the band are left out
                if (!std::isnan(res.pathServed[m][f])) s.x.push_back(res.pathTimes[f]), s.y.push_back(res.pathServed[m][f]);
            s.style = res.pathMethods[m].rfind("interpolative", 0) == 0 ? vtk::ChartSeries::Style::DashedLine : vtk::ChartSeries::Style::Line;
            vtk::paletteColour(int(m % o.sizes.size()), s.rgb);
            path.series.push_back(s);
        }
        writeChart(path, (fs::path(o.e.plots) / ("keypose-path-" + tag + ".png")).string());
    }
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    bench::Experiment experiment("bench_keypose",
                                 "Seed 004's key-pose cache on the town crowd: plain skinning, intermittent and interpolative caches\n"
                                 "of each size, on the identical state, side by side; frame time, cache use and accuracy.",
                                 bench::kScene | bench::kActorList | bench::kCameras | bench::kFrames | bench::kWarmup | bench::kImageSize |
                                     bench::kCsv | bench::kAccuracyCsv | bench::kMarkdown | bench::kPlots | bench::kErrorEvery,
                                 {.scene = testkit::townDefaultScene(), .actors = {10000}, .cameras = {"street", "overview"}, .frames = 20, .warmup = 60,
                                  .errorEvery = 5},
                                 {.accuracyCsvHelp = "write the accuracy rows in the common accuracy CSV",
                                  .errorEveryHelp = "ticks between accuracy measurements"});
    CLI::App& app = experiment.app();
    app.add_option("--sizes", o.sizes, "cache sizes (key-poses per template)")->delimiter(',')->type_name("N,N,...")->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(CLI::Range(std::int64_t(1), std::int64_t(65535)));
    app.add_option("--error-samples", o.errorSamples, "cached actors compared per method and measured tick")
        ->type_name("N")->check(CLI::Range(1, 1'000'000));
    app.add_option("--path-frames", o.pathFrames, "frames along the camera path for the served share (0: skip)")
        ->type_name("N")->check(CLI::Range(0, 1'000'000));
    app.add_option("--distance", o.distance, "start of the cache band, metres (default: the scene's, else 15)")
        ->type_name("M")->check(bench::finiteNumber(1e-6, 1e6));
    app.add_option("--rate", o.rate, "key-poses per second of clip (default: the scene's, else 15)")
        ->type_name("HZ")->check(bench::finiteNumber(1e-6, 1e6));
    app.add_option("--demands", o.demands,
                   "write what the band needed along the camera path, one instance per frame and template (frame,a,b,actors: "
                   "bench_keypose_selection --demands reads it)")
        ->type_name("FILE")->check(bench::fileToWrite());
    experiment.markOutput("--demands");
    app.add_option("--demand-size", o.demandSize, "the interpolative cache size whose demands --demands writes")
        ->type_name("N")->check(CLI::Range(1, 65535));
    if (const auto code = experiment.parse(argc, argv)) return *code;
    o.e = experiment.spec();
    if (!o.demands.empty() && std::find(o.sizes.begin(), o.sizes.end(), o.demandSize) == o.sizes.end())
        fail("--demand-size " + std::to_string(o.demandSize) + " is not one of --sizes");

    std::ostringstream report;
    std::vector<Result> results;
    try {
        auto context = bench::experimentContext(o.e);
        std::ofstream demands;
        if (!o.demands.empty()) {
            demands.open(o.demands);
            if (!demands) fail("cannot write " + o.demands);
            demands << "frame,a,b,actors\n";
        }
        std::uint64_t ticks = 0, instance = 0;
        for (std::int64_t n : o.e.actors) {
            std::fprintf(stderr, "bench_keypose: %lld actors: building, baking impostors, %d ticks per camera...\n", (long long)n, o.e.frames);
            results.push_back(run(o, n, context, demands.is_open() ? &demands : nullptr, &instance));
            ticks += results.back().ticks;
        }
        report << "Identical state: every method saw the same state digest on each of " << ticks << " ticks.\n\n"
               << "Milliseconds per frame, " << o.e.width << " x " << o.e.height << " headless, " << context->description()
               << ", one thread, the GL finished after each pass; means over " << o.e.frames << " ticks (`" << experiment.reproduction();
        std::vector<Row> all;
        for (const Result& r : results) all.insert(all.end(), r.rows.begin(), r.rows.end());
        report << "`). Vertex and image errors against plain skinning of the same tick, every " << o.e.errorEvery << " ticks.\n\n"
               << table(all).markdown();
        if (!o.e.csv.empty()) bench::writeWhole(o.e.csv, table(all).csv());
        if (!o.e.accuracyCsv.empty()) {
            // The common accuracy CSV: one knob per cache mode, plain skinning (the same rows) as
            // each knob's "off"; the time is APP+CULL and DRAW, the two phases the cache changes.
            sim::AccuracyCsv csv(o.e.accuracyCsv);
            const std::string scene = sim::sceneName(o.e.scene);
            for (const char* mode : {"intermittent", "interpolative"}) {
                const bool present = std::any_of(all.begin(), all.end(), [&](const Row& r) { return r.size > 0 && r.method.rfind(mode, 0) == 0; });
                if (!present) continue;
                for (const Row& r : all) {
                    if (r.size > 0 && r.method.rfind(mode, 0) != 0) continue;
                    sim::AccuracyRecord a;
                    a.knob = std::string("key-pose cache size, ") + mode;
                    a.value = r.size == 0 ? "off" : std::to_string(r.size);
                    a.off = r.size == 0;
                    a.metrics = {{"psnr", r.size == 0 ? 99.0 : r.psnr, "dB", false},
                                 {"ssim", r.size == 0 ? 1.0 : r.ssim, "1", false},
                                 {"pixels_off_8", r.off8, "share", true},
                                 {"vertex_error_mean", r.vertexMeanMm(), "mm", true},
                                 {"vertex_error_max", 1000.0 * r.vertexMax, "mm", true},
                                 {"key_pose_error_mean", r.keyMeanMm(), "mm", true},
                                 {"key_pose_error_max", 1000.0 * r.keyMax, "mm", true}};
                    a.ms = r.appCull + r.draw;
                    a.msPhase = "app_cull+draw";
                    a.memoryBytes = r.cacheBytes;
                    a.scene = scene;
                    a.camera = r.camera;
                    a.actors = r.actors;
                    csv.add(a);
                }
            }
        }
        if (!o.e.plots.empty()) {
            if (vtk::displayAvailable()) plots(o, results);
            else std::fprintf(stderr, "bench_keypose: no display, no plots (run under xvfb-run -a)\n");
        }
    } catch (const std::exception& e) {
        fail(e.what());
    }
    std::fputs(report.str().c_str(), stdout);
    try {
        if (!o.e.markdown.empty()) bench::writeWhole(o.e.markdown, report.str());
    } catch (const std::exception& e) {
        fail(e.what());
    }
    return 0;
}
