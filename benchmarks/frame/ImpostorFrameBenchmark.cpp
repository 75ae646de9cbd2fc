// bench_impostor_frame: what far actors cost as impostors, against drawing them as meshes, on the
// identical state (seed 000's claim that impostors are the cheap tier, measured on this GL).
//
// Each tick the simulation steps once, outside every processor; the camera follows the scene's
// path (every method on that camera). Methods, each with its own processor and
// renderer (the GL finished after each pass, so each pass's time holds its rasterisation):
// Measured in runs of consecutive frames from a few points of the camera path (the overview, the
// street, above the roofs), as throng-town would see them.
//   - all skinned: no impostors, no key-pose caches (the reference image);
//   - no impostors: the scene's key-pose caches drawn out to any distance (throng-town
//     --impostor-distance 0);
//   - impostors as before: the frame's morphed cells made through a MorphCache and read back, then
//     uploaded every frame (ImpostorMorphing::FrameCache);
//   - impostors, pool: morphed cells kept on the GPU across frames, at most `--budget` new ones per
//     atlas and frame, made by the GL into the pool (along the bone lines, or through the surface
//     proxy) or on the CPU and uploaded; and the same with no budget (the budget's image error is
//     measured against it);
//   - impostors warped: each drawn as the figure's surface proxy at its own clip time from the
//     real eye, textured from the cells the quad would blend (ImpostorViewChoice::warped);
//   - impostors without looks in the pass: the surface-proxy row's options with the actors' looks
//     left out of the impostor pass (cells as baked, white per region): what diversity costs there;
//   - with --storages, the atlas storages (issue 37 item 3): full, half the key-frames (today's
//     default), half (every other key-frame and view ring), and half at twice the cell size, each
//     drawn as throng-town draws them (surface proxy on another thread, budget 2).
// Reports per method: APP+CULL, DRAW, the impostor pass (selection, batching, morphing, quads),
// cells morphed and deferred per frame, impostor texture bytes, and the image error of the frame
// against all skinned (PSNR, SSIM, share of pixels off by more than 8/255) and, for budgets,
// against the unlimited pool. The state digest must agree for every method of a tick.
//
// `--sections crowd`: seed 000's Table 1, 1k-16k actors in the town all drawn as impostors (impostor
// distance 1 m) from the overview camera, with 0/4/8/12/all feature lines; the impostor pass alone,
// with every cell the frame shows morphed again each frame (the seed's regime) and with our pool.
//
// usage: bench_impostor_frame --help

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "throng/bench/Experiment.h"
#include "throng/bench/FrameWorld.h"
#include "throng/bench/ResultTable.h"
#include "throng/bench/SameState.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/testkit/ImageSimilarity.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/AccuracyCsv.h"
#include "throng/testkit/Assets.h"

using namespace throng;

namespace {

[[noreturn]] void fail(const std::string& why) { bench::fail("bench_impostor_frame", why); }

// The experiment's settings: the common ones (e) and its own.
struct Options {
    bench::ExperimentSpec e;     // scene, actors (one count, 0: the scene's), frames from each start, warmup, size, outputs
    int budget = 16;             // new morphed cells per atlas and frame
    int poolSlots = 48;          // pool layers per atlas
    int gridStep = 4;            // the CPU grid methods' warp grid (pixels)
    std::vector<int> gridBudgets{0, 2, 4, 16};  // budgets of the CPU grid methods (the budget knob)
    std::vector<double> distances{30, 80};      // other impostor distances (the scene's is 40 m)
    std::vector<std::int64_t> crowdActors{1024, 4096, 8192, 16384};
    std::vector<std::int64_t> crowdFeatures{0, 4, 8, 12, 1000};  // 1000: every bone
    int crowdFrames = 12;
    std::vector<std::string> sections{"methods"};
    bool storages = false;       // also the atlas-storage rows (full, half; half at twice the cells)
    bool has(const char* s) const { return std::find(sections.begin(), sections.end(), s) != sections.end(); }
};

enum class Kind { AllSkinned, NoImpostors, Impostors };

struct Method {
    std::string name;
    Kind kind = Kind::Impostors;
    CrowdRendererOptions renderer;
    std::string knob, value;  // its row in the accuracy CSV
    double distance = 0;      // impostor distance (0: the scene's)
    const ImpostorSet* atlases = nullptr;  // its impostors (null: the scene's default bake)
    std::unique_ptr<ActorProcessor> processor;
    std::unique_ptr<CrowdRenderer> draw;
};

// Means over the measured ticks of one method.
struct Row {
    std::string method, knob, value;
    std::size_t actors = 0;
    double appCull = 0, draw = 0, town = 0, meshes = 0, impostor = 0, morph = 0, quads = 0;
    double impostors = 0, morphed = 0, deferred = 0, textureBytes = 0, ticks = 0, background = 0;
    double psnr = 0, ssim = 0, off8 = 0, ncc = 0, images = 0;  // against all skinned (NCC: the whole frame)
    double psnrPool = 0, ssimPool = 0, off8Pool = 0, imagesPool = 0;  // against the unlimited pool
    void add(const ActorFrameStatistics& s, const CrowdRenderStatistics& r, double drawMs) {
        appCull += s.appCullMs();
        draw += drawMs;
        town += r.sceneMs;
        meshes += r.meshMs;
        impostor += r.impostorBatchMs + r.impostorDrawMs;
        morph += r.morphMs;
        quads += r.impostorDrawMs;
        impostors += double(r.quads.instances);
        morphed += double(r.cellsMorphed);
        deferred += double(r.quads.cellsDeferred);
        background += r.quads.backgroundMorphMs;
        ticks += 1;
    }
    void divide() {
        for (double* v : {&appCull, &draw, &town, &meshes, &impostor, &morph, &quads, &impostors, &morphed, &deferred, &background})
            *v /= std::max(ticks, 1.0);
        if (images > 0) psnr /= images, ssim /= images, off8 /= images, ncc /= images;
        if (imagesPool > 0) psnrPool /= imagesPool, ssimPool /= imagesPool, off8Pool /= imagesPool;
    }
};

void compare(const Image& a, const Image& b, double& psnr, double& ssim, double& off8, double& n, double* ncc = nullptr) {
    if (ncc) *ncc += testkit::normalizedCrossCorrelation(a, b, false);
    bench::addFrameError(a, b, psnr, ssim, off8);
    n += 1;
}

CrowdRendererOptions poolOptions(const Options& o, MorphSource source, int budget, int gridStep = 1, bool background = false,
                                 CellWarp warp = CellWarp::FeatureLines) {
    CrowdRendererOptions r;
    r.impostors.warp = warp;
    r.impostors.backgroundMorph = background;
    r.impostors.gridStep = gridStep;
    r.finishPasses = true;
    r.impostors.poolSlots = o.poolSlots;
    r.impostors.morphBudget = budget;
    r.impostors.source = source;
    return r;
}

std::vector<Row> runMethods(const Options& o, const std::shared_ptr<GlContext>& context) {
    auto world = bench::buildWorld(o.e.scene, o.e.actors.front());
    auto impostors = bench::bakeImpostors(context, *world);
    context->resize(o.e.width, o.e.height);
    const auto [distance, hysteresis] = bench::impostorDistance(*world);
    std::vector<Method> methods;
    CrowdRendererOptions finished;
    finished.finishPasses = true;
    CrowdRendererOptions before = finished;
    before.morphing = ImpostorMorphing::FrameCache;
    const auto add = [&](std::string name, Kind kind, const CrowdRendererOptions& r, std::string knob, std::string value, double d = 0) {
        methods.push_back({std::move(name), kind, r, std::move(knob), std::move(value), d, nullptr, nullptr, nullptr});
    };
    const std::string grid = std::to_string(o.gridStep) + " px grid";
    add("all skinned", Kind::AllSkinned, finished, "", "");
    add("no impostors (key-pose caches to any distance)", Kind::NoImpostors, finished, "impostor distance", "none");
    add("impostors as before (frame cache, read back)", Kind::Impostors, before, "impostor morphing", "frame cache, GL, read back");
    add("impostors, pool, GL, budget " + std::to_string(o.budget), Kind::Impostors, poolOptions(o, MorphSource::Gpu, o.budget),
        "impostor morphing", "pool, GL, budget " + std::to_string(o.budget));
    add("impostors, pool, GL through the surface proxy, budget " + std::to_string(o.budget), Kind::Impostors,
        poolOptions(o, MorphSource::Gpu, o.budget, 1, false, CellWarp::SurfaceProxy), "impostor morphing",
        "pool, GL, surface proxy, budget " + std::to_string(o.budget));
    add("impostors, pool, CPU, budget " + std::to_string(o.budget), Kind::Impostors, poolOptions(o, MorphSource::Cpu, o.budget),
        "impostor morphing", "pool, CPU, budget " + std::to_string(o.budget));
    for (int budget : o.gridBudgets)
        add(budget == 0 ? std::string("impostors, pool, no morphing (budget 0: nearest stored key-frame)")
                        : "impostors, pool, CPU on a " + grid + ", budget " + std::to_string(budget),
            Kind::Impostors, poolOptions(o, MorphSource::Cpu, budget, o.gridStep), "morph budget", std::to_string(budget));
    for (int budget : o.gridBudgets)
        if (budget > 0)
            add("impostors, pool, CPU on a " + grid + " on another thread, budget " + std::to_string(budget), Kind::Impostors,
                poolOptions(o, MorphSource::Cpu, budget, o.gridStep, true), "morph budget", std::to_string(budget) + " on another thread");
    for (int budget : o.gridBudgets)
        if (budget > 0)
            add("impostors, pool, surface proxy on another thread, budget " + std::to_string(budget), Kind::Impostors,
                poolOptions(o, MorphSource::Cpu, budget, o.gridStep, true, CellWarp::SurfaceProxy), "morph budget",
                std::to_string(budget) + " on another thread, surface proxy");
    {
        // Each impostor drawn as its surface proxy at its clip time from the real eye (seed 003
        // §4.1), its cells made as throng-town makes them: against the quad row above.
        CrowdRendererOptions warped = poolOptions(o, MorphSource::Cpu, 2, o.gridStep, true, CellWarp::SurfaceProxy);
        warped.views.warped = true;
        add("impostors warped (the proxy per impostor), pool, surface proxy on another thread, budget 2", Kind::Impostors, warped,
            "impostor views", "warped");
    }
    {
        // The same as the surface-proxy row at budget 2, but the pass draws the cells as baked,
        // without the looks' region lookups: what crowd diversity costs in the impostor pass.
        CrowdRendererOptions plain = poolOptions(o, MorphSource::Cpu, 2, o.gridStep, true, CellWarp::SurfaceProxy);
        plain.impostors.bodyLooks = false;
        add("impostors without looks in the pass, pool, surface proxy on another thread, budget 2", Kind::Impostors, plain,
            "impostor looks", "off");
    }
    for (double d : o.distances)
        add("impostors from " + std::to_string(int(d)) + " m, pool, surface proxy on another thread, budget 2", Kind::Impostors,
            poolOptions(o, MorphSource::Cpu, 2, o.gridStep, true, CellWarp::SurfaceProxy), "impostor distance", std::to_string(int(d)), d);
    // The atlas storages (issue 37 item 3), each drawn as throng-town draws by default (surface
    // proxy, CPU on another thread, budget 2): the same crowd, only what the atlases keep differs.
    struct Storage {
        AtlasStorage storage;
        int cellSize;
        const char* name;
    };
    std::vector<std::unique_ptr<ImpostorSet>> storageSets;
    if (o.storages)
        for (const Storage& st : {Storage{AtlasStorage::Full, 64, "full atlas, 64 px"}, Storage{AtlasStorage::HalfKeyframes, 64, "half the key-frames, 64 px"},
                                  Storage{AtlasStorage::Half, 64, "half atlas, 64 px"}, Storage{AtlasStorage::Half, 128, "half atlas, 128 px"}}) {
            std::fprintf(stderr, "bench_impostor_frame: baking the %s\n", st.name);
            storageSets.push_back(bench::bakeImpostors(context, *world, st.storage, st.cellSize));
            add(std::string("impostors, ") + st.name + ", pool, surface proxy on another thread, budget 2", Kind::Impostors,
                poolOptions(o, MorphSource::Cpu, 2, o.gridStep, true, CellWarp::SurfaceProxy), "impostor atlas storage", st.name);
            methods.back().atlases = storageSets.back().get();
        }
    context->resize(o.e.width, o.e.height);
    add("impostors, pool, GL, no budget", Kind::Impostors, poolOptions(o, MorphSource::Gpu, -1), "morph budget", "unlimited");
    const std::size_t unlimited = methods.size() - 1;
    const auto& declared = world->description().representation;
    for (Method& m : methods) {
        const ImpostorSet& set = m.atlases ? *m.atlases : *impostors;
        std::vector<std::shared_ptr<const ImpostorDrawable>> drawables;
        for (std::size_t i = 0; i < set.size(); ++i) drawables.push_back(set.drawable(i));
        m.processor = std::make_unique<ActorProcessor>(world->crowd());
        if (declared.occlusion) m.processor->setOcclusion(declared.occlusion);
        if (m.kind != Kind::AllSkinned) world->attachKeyPoseCaches(*m.processor);
        if (m.kind == Kind::Impostors)
            set.attach(*m.processor, m.distance > 0 ? m.distance : distance, m.distance > 0 ? hysteresis / distance * m.distance : hysteresis);
        m.draw = std::make_unique<CrowdRenderer>(context, m.renderer);
        if (m.kind == Kind::Impostors) m.draw->preloadImpostors(drawables);
    }
    for (int f = 0; f < o.e.warmup; ++f) world->step();
    std::vector<Row> rows(methods.size());
    for (std::size_t m = 0; m < methods.size(); ++m) {
        rows[m].method = methods[m].name;
        rows[m].knob = methods[m].knob;
        rows[m].value = methods[m].value;
        rows[m].actors = world->crowd().size();
    }
    const double aspect = double(o.e.width) / double(o.e.height);
    std::vector<Image> frames(methods.size());
    const double step = world->description().step;
    for (double start : o.e.starts)
    for (int f = -2; f < o.e.frames; ++f) {  // two unmeasured ticks warm the GL and the pools
        const FrameContext& now = world->step();
        const Camera camera = world->camera().at(start + step * (f + 2), aspect);
        const bool measureError = f >= 0 && f % o.e.errorEvery == 0;
        bench::runOnSameState(world->crowd(), methods.size(), f + 2, [&](std::size_t m) {
            const ActorFrameStatistics s = methods[m].processor->processFrame(world->root(), camera, now.time);
            Stopwatch watch;
            methods[m].draw->drawFrame(camera, methods[m].processor->drawList());
            const double drawMs = watch.elapsedMs();
            if (f < 0) return;
            rows[m].add(s, methods[m].draw->statistics(), drawMs);
            if (measureError) frames[m] = methods[m].draw->readFrame();
        }, [&](std::size_t m) { return methods[m].name; });
        if (!measureError) continue;
        for (std::size_t m = 1; m < methods.size(); ++m) {
            compare(frames[m], frames[0], rows[m].psnr, rows[m].ssim, rows[m].off8, rows[m].images, &rows[m].ncc);
            if (methods[m].kind == Kind::Impostors && m != unlimited && methods[m].distance == 0)
                compare(frames[m], frames[unlimited], rows[m].psnrPool, rows[m].ssimPool, rows[m].off8Pool, rows[m].imagesPool);
        }
    }
    for (std::size_t m = 0; m < methods.size(); ++m) {
        rows[m].textureBytes = double(methods[m].draw->impostorTextureBytes());
        rows[m].divide();
    }
    std::fprintf(stderr, "bench_impostor_frame: %zu actors, %zu runs of %d frames along the path done\n", world->crowd().size(),
                 o.e.starts.size(), o.e.frames);
    return rows;
}

std::string methodsTable(const std::vector<Row>& rows) {
    bench::ResultTable t({{"", "method", "%s", true}, {"", "APP+CULL", "%.2f"}, {"", "DRAW", "%.1f"}, {"", "town", "%.1f"}, {"", "meshes", "%.1f"},
                          {"", "impostor pass", "%.2f"}, {"", "of which morphing", "%.2f"}, {"", "quads", "%.2f"},
                          {"", "morphing on another thread", "%.2f"}, {"", "impostors", "%.0f"}, {"", "cells morphed", "%.1f"},
                          {"", "cells deferred", "%.1f"}, {"", "impostor texture MiB", "%.1f"}, {"", "PSNR dB", "%s"}, {"", "SSIM", "%s"},
                          {"", "NCC", "%s"}, {"", "pixels off > 8", "%s"}, {"", "vs unlimited pool: PSNR / SSIM / off > 8", "%s", true}});
    for (const Row& r : rows) {
        const bool img = r.images > 0, pool = r.imagesPool > 0;
        t.add({r.method, r.appCull, r.draw, r.town, r.meshes, r.impostor, r.morph, r.quads, r.background, r.impostors, r.morphed, r.deferred,
               r.textureBytes / 1048576.0, img ? std::to_string(r.psnr).substr(0, 5) : "-", img ? std::to_string(r.ssim).substr(0, 6) : "-",
               img ? std::to_string(r.ncc).substr(0, 6) : "-", img ? std::to_string(100.0 * r.off8).substr(0, 5) + " %" : "-",
               pool ? std::to_string(r.psnrPool).substr(0, 5) + " / " + std::to_string(r.ssimPool).substr(0, 6) + " / " +
                          std::to_string(100.0 * r.off8Pool).substr(0, 5) + " %"
                    : "-"});
    }
    return t.markdown();
}

// Seed 000's Table 1: every actor an impostor, the overview camera; the impostor pass per crowd
// size, feature count and morph path (each its own renderer, taking turns on the same frames).
std::string runCrowd(const Options& o, const std::shared_ptr<GlContext>& context) {
    bench::ResultTable t({{"", "actors", "%lld"}, {"", "features", "%s"}, {"", "morphing", "%s", true}, {"", "impostor pass ms", "%.1f"},
                          {"", "of which morphing", "%.1f"}, {"", "quads", "%.1f"}, {"", "fps of the pass", "%.0f"},
                          {"", "morphing on another thread", "%.1f"}, {"", "impostors", "%.0f"}, {"", "cells morphed", "%.1f"}});
    for (std::int64_t actors : o.crowdActors) {
        auto world = bench::buildWorld(o.e.scene, actors);
        auto impostors = bench::bakeImpostors(context, *world);
        context->resize(o.e.width, o.e.height);
        std::vector<std::shared_ptr<const ImpostorDrawable>> drawables;
        for (std::size_t i = 0; i < impostors->size(); ++i) drawables.push_back(impostors->drawable(i));
        struct CrowdMethod {
            std::string name;
            std::size_t features = 0;
            CrowdRendererOptions options;
            std::unique_ptr<CrowdRenderer> draw;
            double pass = 0, morph = 0, quads = 0, background = 0, impostors = 0, morphed = 0, draws = 0;
        };
        std::vector<CrowdMethod> methods;
        for (std::int64_t features : o.crowdFeatures) {
            // The seed's regime: every cell the frame shows morphed again each frame.
            CrowdRendererOptions everyFrame;
            everyFrame.finishPasses = true;
            everyFrame.morphing = ImpostorMorphing::FrameCache;
            everyFrame.morph.capacity = 0;
            everyFrame.morph.features = std::size_t(features);
            CrowdRendererOptions ours = poolOptions(o, MorphSource::Cpu, 2, o.gridStep, true);  // lines: the features are the knob
            ours.impostors.morph.features = std::size_t(features);
            methods.push_back({"every cell each frame (GL, read back)", std::size_t(features), everyFrame, nullptr});
            methods.push_back({"pool, grid on another thread, budget 2", std::size_t(features), ours, nullptr});
        }
        for (CrowdMethod& m : methods) {
            m.draw = std::make_unique<CrowdRenderer>(context, m.options);
            m.draw->preloadImpostors(drawables);
        }
        ActorProcessor processor(world->crowd());
        impostors->attach(processor, 1.0, 0.0);
        for (int f = 0; f < o.e.warmup; ++f) world->step();
        const Camera camera = world->camera().at(bench::cameraTime("overview"), double(o.e.width) / double(o.e.height));
        for (int f = -2; f < o.crowdFrames; ++f) {
            const FrameContext& now = world->step();
            processor.processFrame(world->root(), camera, now.time);
            for (std::size_t i = 0; i < methods.size(); ++i) {
                CrowdMethod& m = methods[(i + std::size_t(f + 2)) % methods.size()];
                m.draw->drawFrame(camera, processor.drawList());
                if (f < 0) continue;
                const CrowdRenderStatistics& r = m.draw->statistics();
                m.pass += r.impostorBatchMs + r.impostorDrawMs;
                m.morph += r.morphMs;
                m.quads += r.impostorDrawMs;
                m.background += r.quads.backgroundMorphMs;
                m.impostors += double(r.quads.instances);
                m.morphed += double(r.cellsMorphed);
                m.draws += 1;
            }
        }
        for (const CrowdMethod& m : methods) {
            const double n = std::max(m.draws, 1.0);
            t.add({std::int64_t(world->crowd().size()), m.features >= 1000 ? std::string("all") : std::to_string(m.features), m.name, m.pass / n,
                   m.morph / n, m.quads / n, 1000.0 * n / std::max(m.pass, 1e-9), m.background / n, m.impostors / n, m.morphed / n});
        }
        std::fprintf(stderr, "bench_impostor_frame: crowd of %zu done\n", world->crowd().size());
    }
    return t.markdown();
}

// The common accuracy CSV: one record per knob setting, its image error against all skinned and its
// DRAW time. "none" (no impostors) and "unlimited" (no morph budget) switch their knob off.
void writeAccuracyCsv(const std::string& path, const std::vector<Row>& rows, const Options& o) {
    sim::AccuracyCsv csv(path);
    for (const Row& r : rows) {
        if (r.images == 0 || r.knob.empty()) continue;
        sim::AccuracyRecord a;
        a.knob = r.knob;
        a.value = r.value;
        a.off = (r.knob == "impostor distance" && r.value == "none") || (r.knob == "morph budget" && r.value == "unlimited");
        a.metrics = {{"psnr", r.psnr, "dB", false}, {"ssim", r.ssim, "1", false}, {"pixels_off_8", r.off8, "share", true}};
        a.ms = r.draw;
        a.msPhase = "draw";
        a.memoryBytes = r.textureBytes;
        a.scene = sim::sceneName(o.e.scene);
        a.camera = "path";
        a.actors = std::int64_t(r.actors);
        csv.add(a);
    }
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    bench::Experiment experiment("bench_impostor_frame",
                                 "Far actors as impostors against drawing them as meshes, on the identical state: APP+CULL, DRAW, the "
                                 "impostor pass and its morphing, and the image error against all skinned.",
                                 bench::kScene | bench::kActorCount | bench::kFrames | bench::kWarmup | bench::kImageSize | bench::kMarkdown |
                                     bench::kAccuracyCsv | bench::kStarts | bench::kErrorEvery,
                                 {.scene = testkit::townDefaultScene(), .actors = {0}, .frames = 16, .warmup = 30, .starts = {0.0, 9.0, 15.0},
                                  .errorEvery = 4},
                                 {.frames = "--frames", .framesHelp = "measured ticks from each start, the camera following its path",
                                  .accuracyCsvHelp = "write the methods' image error and DRAW time in the common accuracy CSV"});
    CLI::App& app = experiment.app();
    app.add_option("--grid", o.gridStep, "warp grid (pixels) of the CPU grid methods")->type_name("N")->check(CLI::Range(2, 64));
    app.add_option("--distances", o.distances, "other impostor distances (m), each with the default morphing")->delimiter(',')
        ->type_name("M,M,...")->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(bench::finiteNumber(1e-3, 1e6));
    app.add_option("--grid-budgets", o.gridBudgets, "budgets of the CPU grid methods")->delimiter(',')->type_name("N,N,...")->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(CLI::Range(0, 100000));
    app.add_option("--budget", o.budget, "new morphed cells per atlas and frame for the budgeted pools")->type_name("N")->check(CLI::Range(0, 100000));
    app.add_option("--pool", o.poolSlots, "pool layers per atlas")->type_name("N")->check(CLI::Range(1, 2048));
    app.add_option("--crowd-actors", o.crowdActors, "crowd sizes of the crowd section")->delimiter(',')->type_name("N,N,...")->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(CLI::Range(1, 10'000'000));
    app.add_option("--crowd-features", o.crowdFeatures, "feature lines of the crowd section (1000: every bone)")->delimiter(',')
        ->type_name("N,N,...")->check(CLI::Range(0, 1000));
    app.add_option("--crowd-frames", o.crowdFrames, "measured frames of the crowd section")->type_name("N")->check(CLI::Range(1, 100000));
    app.add_flag("--storages", o.storages,
                 "also draw with the atlas storages side by side: full, half the key-frames (the default), half (every other key-frame "
                 "and view ring), half at 128 px cells (bakes four more sets)");
    app.add_option("--sections", o.sections, "what to run: methods (the scene along its camera path), crowd (seed 000's 16,384 impostors)")
        ->delimiter(',')->type_name("NAME,...")->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(CLI::IsMember({"methods", "crowd"}));
    if (const auto code = experiment.parse(argc, argv)) return *code;
    o.e = experiment.spec();
    std::ostringstream report;
    try {
        auto context = bench::experimentContext(o.e);
        if (o.has("methods")) {
            const std::vector<Row> rows = runMethods(o, context);
            report << "### " << (o.e.actors.front() ? std::to_string(o.e.actors.front()) : std::string("the scene's")) << " actors, " << o.e.frames
                   << " frames from each of " << o.e.starts.size() << " points of the camera path, " << o.e.width << "x" << o.e.height << " (ms per frame)\n\n"
                   << methodsTable(rows) << "\n";
            if (!o.e.accuracyCsv.empty()) writeAccuracyCsv(o.e.accuracyCsv, rows, o);
        }
        if (o.has("crowd")) report << "### Seed 000's Table 1: every actor an impostor, the overview camera (ms per frame)\n\n" << runCrowd(o, context) << "\n";
        std::fputs(report.str().c_str(), stdout);
        if (!o.e.markdown.empty()) bench::writeWhole(o.e.markdown, report.str());
    } catch (const std::exception& e) {
        fail(e.what());
    }
    return 0;
}
