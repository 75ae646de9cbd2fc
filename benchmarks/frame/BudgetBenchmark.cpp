// bench_budget: the ladder of throng-town --frame-budget, measured. Each rung is a setting of the
// knobs that trade image error for time (LOD scale, impostor distance, key-pose distance, morph
// budget); every rung, and the frame-budget allocator at each budget asked for, runs with its own
// processor and renderer on the identical states (the simulation steps once per tick, outside every
// processor; the camera follows the scene's path from a few starts), with throng-town's renderer
// options (impostor cells morphed on a 4 px grid on another thread, surface proxy; no pipeline).
//
// Cost: APP+CULL (the processor's phases) + DRAW (drawFrame, its rasterisation included) per frame.
// Error: the frame against the reference, the same state with every approximation of the ladder
// off (no impostors, no key-pose caches, skeletal and behavioural LOD off, LOD scale 0.01 so every
// part is at its finest level; occlusion culling as the scene declares it, as in every rung): PSNR,
// SSIM and the share of pixels off by more than 8/255 (ImageCompare.h, ImageSimilarity.h).
//
// Writes the ladder (--ladder FILE, the common accuracy CSV, knob "frame budget rung"): the rungs
// on the Pareto front (each cheaper than every more accurate one), most accurate first; throng-town
// reads it with --frame-budget-ladder. Prints a Markdown table of every rung and, per budget, the
// allocator's share of frames within budget, mean cost and error against the most accurate fixed
// rung whose mean cost is not above the allocator's.
//
// usage: bench_budget --help

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
#include "throng/sim/BudgetLadder.h"
#include "throng/sim/FrameBudgetAllocator.h"
#include "throng/testkit/Assets.h"

using namespace throng;
using sim::BudgetRung;
using sim::BudgetSettings;

namespace {

// The experiment's own settings (the common ones are in bench::ExperimentSpec).
struct Options {
    std::vector<std::string> rungs{
        "lod-scale=0.5 impostor-distance=120 key-pose-distance=60 morph-budget=16",
        "lod-scale=0.75 impostor-distance=80 key-pose-distance=40 morph-budget=8",
        "lod-scale=1 impostor-distance=60 key-pose-distance=30 morph-budget=4",
        "lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2",
        "lod-scale=1.5 impostor-distance=30 key-pose-distance=15 morph-budget=2",
        "lod-scale=2 impostor-distance=20 key-pose-distance=10 morph-budget=1",
        "lod-scale=3 impostor-distance=12 key-pose-distance=6 morph-budget=0",
        "lod-scale=4 impostor-distance=6 key-pose-distance=3 morph-budget=0",
        "lod-scale=3 impostor-distance=12 key-pose-distance=6 morph-budget=0 render-scale=0.75",
        "lod-scale=3 impostor-distance=12 key-pose-distance=6 morph-budget=0 render-scale=0.5",
        "lod-scale=4 impostor-distance=6 key-pose-distance=3 morph-budget=0 render-scale=0.5",
        "lod-scale=4 impostor-distance=6 key-pose-distance=3 morph-budget=0 render-scale=0.35",
        "lod-scale=4 impostor-distance=6 key-pose-distance=3 morph-budget=0 render-scale=0.5 town-lod-scale=1",
        "lod-scale=4 impostor-distance=6 key-pose-distance=3 morph-budget=0 render-scale=0.35 town-lod-scale=1",
        "lod-scale=4 impostor-distance=6 key-pose-distance=3 morph-budget=0 render-scale=0.35 town-lod-scale=3",
    };
    std::vector<double> budgets;
    std::string ladder;
    std::string fromLadder;  // measure no rung: run the allocators on this ladder
};

// One way of drawing the ticks: a fixed rung, the allocator at a budget, or the reference.
struct Method {
    std::string name;
    BudgetSettings settings;
    std::unique_ptr<sim::FrameBudgetAllocator> allocator;  // null: fixed
    int rung = -1;                                              // the allocator's current rung
    std::unique_ptr<ActorProcessor> processor;
    std::unique_ptr<CrowdRenderer> draw;
    double ms = 0, frames = 0, within = 0;
    double psnr = 0, ssim = 0, off8 = 0, images = 0;
    std::vector<int> histogram;
};

// The town's LOD scale is the world's (scene data, shared by every method): set before each
// method's APP and CULL, as throng-town sets it between frames.
void apply(ActorProcessor& p, CrowdRenderer& r, const BudgetSettings& s, double hysteresisShare, bool caches) {
    p.setLodScale(s.lodScale);
    p.setImpostorDistance(s.impostorDistance, hysteresisShare * s.impostorDistance);
    if (caches) p.setKeyPoseDistance(s.keyPoseDistance, hysteresisShare * s.keyPoseDistance);
    r.setMorphBudget(s.morphBudget);
    r.setRenderScale(float(s.renderScale));
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    bench::Experiment experiment("bench_budget",
                                 "The ladder of throng-town --frame-budget: each rung's APP+CULL+DRAW and image error against every "
                                 "approximation off, on the identical states; the allocator at each --budgets against the fixed rungs.",
                                 bench::kScene | bench::kActorCount | bench::kFrames | bench::kWarmup | bench::kImageSize | bench::kMarkdown |
                                     bench::kStarts | bench::kErrorEvery,
                                 {.scene = testkit::townDefaultScene(), .actors = {10000}, .frames = 12, .warmup = 30, .starts = {0.0, 9.0, 15.0},
                                  .errorEvery = 3},
                                 {.frames = "--frames", .framesHelp = "measured ticks from each start"});
    CLI::App& app = experiment.app();
    app.add_option("--rungs", o.rungs, "the candidate rungs, most accurate first ('lod-scale=X impostor-distance=D key-pose-distance=K morph-budget=N [render-scale=S] [town-lod-scale=T]')")
        ->delimiter(';')->type_name("RUNG;RUNG;...")->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--budgets", o.budgets, "also run the allocator at these budgets (ms) on the measured ladder")->delimiter(',')
        ->type_name("MS,MS,...")->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(bench::finiteNumber(1e-3, 1e6));
    app.add_option("--ladder", o.ladder, "write the ladder (Pareto front, most accurate first) as the common accuracy CSV")->type_name("FILE")
        ->check(bench::fileToWrite());
    app.add_option("--from-ladder", o.fromLadder, "skip measuring the rungs: run the --budgets allocators on this ladder (and its rungs)")
        ->type_name("FILE")->check(CLI::ExistingFile);
    experiment.markOutput("--ladder");
    if (const auto code = experiment.parse(argc, argv)) return *code;
    const bench::ExperimentSpec& e = experiment.spec();

    std::vector<BudgetSettings> candidates;
    for (const std::string& v : o.rungs) try {
        candidates.push_back(sim::parseBudgetRungValue(v));
    } catch (const std::invalid_argument& ex) {
        std::fprintf(stderr, "bench_budget: --rungs: '%s': %s\n", v.c_str(), ex.what());
        return bench::Experiment::kUsageError;
    }
    std::ostringstream report;
    try {
        auto context = bench::experimentContext(e);
        experiment.progress("building the world");
        auto world = bench::buildWorld(e.scene, e.actors.front());
        experiment.progress("baking impostors");
        auto impostors = bench::bakeImpostors(context, *world);
        context->resize(e.width, e.height);
        const auto& declared = world->description().representation;
        const double hysteresis = declared.hysteresis;
        const bool caches = declared.keyPoseCache.has_value();
        const double townLodScale = world->townLodScale();
        std::vector<std::shared_ptr<const ImpostorDrawable>> drawables;
        for (std::size_t i = 0; i < impostors->size(); ++i) drawables.push_back(impostors->drawable(i));
        CrowdRendererOptions town;  // throng-town's defaults
        town.impostors.gridStep = 4;
        town.impostors.backgroundMorph = true;
        town.impostors.warp = CellWarp::SurfaceProxy;
        town.impostors.source = MorphSource::Cpu;

        // The reference: every approximation of the ladder off.
        Method reference;
        reference.processor = std::make_unique<ActorProcessor>(world->crowd());
        if (declared.occlusion) reference.processor->setOcclusion(declared.occlusion);
        reference.processor->setSkeletalLod(false);
        reference.processor->setBehaviouralLod(false);
        reference.processor->setLodScale(0.01);
        reference.draw = std::make_unique<CrowdRenderer>(context, town);

        auto makeMethod = [&](std::string name, const BudgetSettings& s) {
            Method m;
            m.name = std::move(name);
            m.settings = s;
            m.processor = std::make_unique<ActorProcessor>(world->crowd());
            if (declared.occlusion) m.processor->setOcclusion(declared.occlusion);
            if (caches)
                for (auto& cache : world->makeKeyPoseCaches()) m.processor->setKeyPoseCache(std::move(cache));
            impostors->attach(*m.processor, std::max(s.impostorDistance, 1.0), 0.0);
            m.draw = std::make_unique<CrowdRenderer>(context, town);
            m.draw->preloadImpostors(drawables);
            apply(*m.processor, *m.draw, s, hysteresis, caches);
            return m;
        };
        std::vector<Method> methods;
        if (o.fromLadder.empty())
            for (const BudgetSettings& s : candidates) methods.push_back(makeMethod(sim::budgetRungValue(s), s));
        const std::size_t fixedCount = methods.size();

        // Runs `ms` on the next ticks (the allocator needs the ladder's times before its run, so the
        // rungs are measured first and the allocators run on later ticks beside the ladder's rungs).
        auto runTicks = [&](std::vector<Method>& ms, bool withReference, const char* what) {
            for (Method& m : ms) m.ms = m.frames = m.within = m.psnr = m.ssim = m.off8 = m.images = 0;
            const double aspect = double(e.width) / double(e.height);
            const double step = world->description().step;
            std::vector<Image> frames(ms.size());
            int tick = 0;
            const int total = int(e.starts.size()) * (e.frames + 2);
            for (double start : e.starts)
                for (int f = -2; f < e.frames; ++f, ++tick) {
                    const FrameContext& now = world->step();
                    const Camera camera = world->camera().at(start + step * (f + 2), aspect);
                    const bool measureError = withReference && f >= 0 && f % e.errorEvery == 0;
                    bench::runOnSameState(world->crowd(), ms.size(), tick, [&](std::size_t v) {
                        Method& m = ms[v];
                        if (m.allocator) {
                            m.settings = m.allocator->ladder()[std::size_t(m.rung)].settings;
                            apply(*m.processor, *m.draw, m.settings, hysteresis, caches);
                        }
                        world->setTownLodScale(m.settings.townLodScale > 0.0 ? m.settings.townLodScale : townLodScale);
                        const ActorFrameStatistics s = m.processor->processFrame(world->root(), camera, now.time);
                        Stopwatch watch;
                        m.draw->drawFrame(camera, m.processor->drawList());
                        const double cost = s.appCullMs() + watch.elapsedMs();
                        if (m.allocator) {
                            const int used = m.rung;
                            m.rung = m.allocator->observe(used, cost);
                            if (f >= 0) m.histogram[std::size_t(used)]++;
                            if (f >= 0) m.within += cost <= m.allocator->options().budgetMs ? 1 : 0;
                        }
                        if (f < 0) return;
                        m.ms += cost;
                        m.frames += 1;
                        if (measureError) frames[v] = m.draw->readFrame();
                    }, [&](std::size_t v) { return ms[v].name; });
                    if (measureError) {
                        world->setTownLodScale(townLodScale);
                        reference.processor->processFrame(world->root(), camera, now.time);
                        reference.draw->drawFrame(camera, reference.processor->drawList());
                        const Image ref = reference.draw->readFrame();
                        for (std::size_t m = 0; m < ms.size(); ++m) {
                            bench::addFrameError(frames[m], ref, ms[m].psnr, ms[m].ssim, ms[m].off8);
                            ms[m].images += 1;
                        }
                    }
                    std::fprintf(stderr, "\r%s: %s: tick %d/%d   ", experiment.program().c_str(), what, tick + 1, total);
                }
            std::fprintf(stderr, "\n");
            for (Method& m : ms) {
                m.ms /= std::max(m.frames, 1.0);
                if (m.images > 0) m.psnr /= m.images, m.ssim /= m.images, m.off8 /= m.images;
            }
        };
        for (int f = 0; f < e.warmup; ++f) world->step();
        if (!methods.empty()) runTicks(methods, true, "rungs");

        // The ladder: by error, then only rungs cheaper than every more accurate one.
        std::vector<std::size_t> order(fixedCount);
        for (std::size_t i = 0; i < fixedCount; ++i) order[i] = i;
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return methods[a].off8 < methods[b].off8; });
        std::vector<std::size_t> front;
        for (std::size_t i : order)
            if (front.empty() || methods[i].ms < methods[front.back()].ms) front.push_back(i);
        std::vector<BudgetRung> ladder;
        for (std::size_t i : front)
            ladder.push_back({methods[i].settings, methods[i].off8, methods[i].psnr, methods[i].ssim, methods[i].ms});
        if (!o.fromLadder.empty()) ladder = sim::readBudgetLadder(o.fromLadder);

        if (fixedCount > 0) {
            report << "### " << world->crowd().size() << " actors, " << e.frames << " frames from each of " << e.starts.size()
                   << " points of the camera path, " << e.width << "x" << e.height << "\n\n";
            bench::ResultTable rungs({{"", "rung", "%s", true}, {"", "APP+CULL+DRAW ms", "%.1f"}, {"", "PSNR dB", "%.2f"}, {"", "SSIM", "%.4f"},
                                      {"", "pixels off > 8", "%.2f %%"}, {"", "on the ladder", "%s", true}});
            for (std::size_t i = 0; i < fixedCount; ++i) {
                const Method& m = methods[i];
                const auto at = std::find(front.begin(), front.end(), i);
                rungs.add({m.name, m.ms, m.psnr, m.ssim, 100.0 * m.off8,
                           at == front.end() ? std::string("no (dominated)") : "rung " + std::to_string(at - front.begin())});
            }
            report << rungs.markdown();
        }
        if (!o.ladder.empty() && o.fromLadder.empty()) {
            sim::AccuracyCsv csv(o.ladder);
            for (const BudgetRung& r : ladder) {
                sim::AccuracyRecord rec;
                rec.knob = sim::kBudgetRungKnob;
                rec.value = sim::budgetRungValue(r.settings);
                rec.metrics = {{"pixels_off_8", r.error, "share", true}, {"psnr", r.psnr, "dB", false}, {"ssim", r.ssim, "1", false}};
                rec.ms = r.ms;
                rec.msPhase = "app_cull_draw";
                rec.scene = sim::sceneName(e.scene);
                rec.camera = "path";
                rec.actors = std::int64_t(world->crowd().size());
                csv.add(rec);
            }
        }

        // The allocator at each budget against every fixed rung of the ladder, on new ticks.
        if (!o.budgets.empty()) {
            std::vector<Method> second;
            for (const BudgetRung& r : ladder) second.push_back(makeMethod(sim::budgetRungValue(r.settings), r.settings));
            const std::size_t fixed = second.size();
            for (double b : o.budgets) {
                sim::FrameBudgetOptions bo;
                bo.budgetMs = b;
                Method m = makeMethod("allocator, budget " + std::to_string(int(b)) + " ms", ladder.back().settings);
                m.allocator = std::make_unique<sim::FrameBudgetAllocator>(ladder, bo);
                m.rung = m.allocator->rung();
                m.histogram.assign(ladder.size(), 0);
                second.push_back(std::move(m));
            }
            runTicks(second, true, "allocator");
            bench::ResultTable allocators({{"", "budget", "%.0f"}, {"", "allocator: within budget", "%.1f %%"}, {"", "mean ms", "%.1f"},
                                           {"", "PSNR dB", "%.2f"}, {"", "SSIM", "%.4f"}, {"", "pixels off > 8", "%.2f %%"},
                                           {"", "rungs used", "%s", true}, {"", "best fixed rung not dearer", "%s", true}, {"", "its mean ms", "%s"},
                                           {"", "PSNR dB", "%s"}, {"", "SSIM", "%s"}, {"", "pixels off > 8", "%s"}});
            for (std::size_t a = fixed; a < second.size(); ++a) {
                const Method& m = second[a];
                const Method* best = nullptr;
                for (std::size_t i = 0; i < fixed && !best; ++i)
                    if (second[i].ms <= m.ms) best = &second[i];
                std::string used;
                for (std::size_t r = 0; r < m.histogram.size(); ++r)
                    if (m.histogram[r]) used += (used.empty() ? "" : ", ") + std::to_string(r) + ": " + std::to_string(m.histogram[r]);
                allocators.add({m.allocator->options().budgetMs, 100.0 * m.within / std::max(m.frames, 1.0), m.ms, m.psnr, m.ssim, 100.0 * m.off8, used,
                                best ? best->name : std::string("none (every rung dearer)"), best ? std::to_string(best->ms).substr(0, 6) : "-",
                                best ? std::to_string(best->psnr).substr(0, 5) : "-", best ? std::to_string(best->ssim).substr(0, 6) : "-",
                                best ? std::to_string(100.0 * best->off8).substr(0, 5) + " %" : "-"});
            }
            bench::ResultTable fixedRungs({{"", "rung", "%s", true}, {"", "APP+CULL+DRAW ms", "%.1f"}, {"", "PSNR dB", "%.2f"}, {"", "SSIM", "%.4f"},
                                           {"", "pixels off > 8", "%.2f %%"}});
            for (std::size_t i = 0; i < fixed; ++i) fixedRungs.add({second[i].name, second[i].ms, second[i].psnr, second[i].ssim, 100.0 * second[i].off8});
            report << "\n" << allocators.markdown() << "\nFixed rungs on the same ticks:\n\n" << fixedRungs.markdown();
        }
    } catch (const std::exception& ex) {
        experiment.fail(ex.what());
    }
    std::fputs(report.str().c_str(), stdout);
    try {
        if (!e.markdown.empty()) bench::writeWhole(e.markdown, report.str());
    } catch (const std::exception& ex) {
        experiment.fail(ex.what());
    }
    return 0;
}
