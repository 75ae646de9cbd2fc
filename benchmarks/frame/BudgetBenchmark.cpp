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

#include "throng/bench/FrameWorld.h"
#include "throng/testkit/Assets.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/testkit/ImageSimilarity.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/AccuracyCsv.h"
#include "throng/sim/BudgetLadder.h"
#include "throng/support/CommandLine.h"
#include "throng/sim/FrameBudgetAllocator.h"
#include "throng/support/Validators.h"

using namespace throng;
using sim::BudgetRung;
using sim::BudgetSettings;

namespace {

[[noreturn]] void fail(const std::string& why) { bench::fail("bench_budget", why); }

struct Options {
    std::int64_t actors = 10000;
    std::vector<double> starts{0.0, 9.0, 15.0};
    int frames = 12;
    int warmup = 30;
    int errorEvery = 3;
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
    int width = 1280, height = 720;
    std::string scene = testkit::townDefaultScene();
    std::string ladder, markdown;
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
    using support::wholeNumber;
    Options o;
    support::CommandLine cl("bench_budget",
                            "The ladder of throng-town --frame-budget: each rung's APP+CULL+DRAW and image error against every "
                            "approximation off, on the identical states; the allocator at each --budgets against the fixed rungs.");
    CLI::App& app = cl.app();
    app.add_option("--scene", o.scene, "scene file")->type_name("FILE")->check(support::existingFile());
    app.add_option("--actors", o.actors, "actors (0: the scene's own count)")->type_name("N")->check(wholeNumber(0, 10'000'000))->capture_default_str();
    app.add_option("--starts", o.starts, "camera path times (s) where measured runs start")->delimiter(',')->type_name("T,T,...")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--frames", o.frames, "measured ticks from each start")->type_name("N")->check(wholeNumber(1, 100000))->capture_default_str();
    app.add_option("--warmup", o.warmup, "ticks simulated first")->type_name("N")->check(wholeNumber(0, 100000))->capture_default_str();
    app.add_option("--error-every", o.errorEvery, "ticks between image comparisons")->type_name("N")->check(wholeNumber(1, 100000))->capture_default_str();
    app.add_option("--rungs", o.rungs, "the candidate rungs, most accurate first ('lod-scale=X impostor-distance=D key-pose-distance=K morph-budget=N [render-scale=S] [town-lod-scale=T]')")
        ->delimiter(';')->type_name("RUNG;RUNG;...");
    app.add_option("--budgets", o.budgets, "also run the allocator at these budgets (ms) on the measured ladder")->delimiter(',')
        ->type_name("MS,MS,...")->check(CLI::PositiveNumber);
    app.add_option("--width", o.width, "image width")->type_name("W")->check(wholeNumber(16, 8192))->capture_default_str();
    app.add_option("--height", o.height, "image height")->type_name("H")->check(wholeNumber(16, 8192))->capture_default_str();
    app.add_option("--ladder", o.ladder, "write the ladder (Pareto front, most accurate first) as the common accuracy CSV")->type_name("FILE");
    app.add_option("--from-ladder", o.fromLadder, "skip measuring the rungs: run the --budgets allocators on this ladder (and its rungs)")
        ->type_name("FILE")->check(support::existingFile());
    app.add_option("--markdown", o.markdown, "also write the tables as Markdown")->type_name("FILE");
    if (const auto code = cl.parse(argc, argv)) return *code;

    std::vector<BudgetSettings> candidates;
    for (const std::string& v : o.rungs) try {
        candidates.push_back(sim::parseBudgetRungValue(v));
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "bench_budget: --rungs: '%s': %s\n", v.c_str(), e.what());
        return 2;
    }
    std::ostringstream report;
    try {
        auto context = createContext({.width = o.width, .height = o.height, .window = false});
        std::fprintf(stderr, "bench_budget: building the world\n");
        auto world = bench::buildWorld(o.scene, o.actors);
        std::fprintf(stderr, "bench_budget: baking impostors\n");
        auto impostors = bench::bakeImpostors(context, *world);
        context->resize(o.width, o.height);
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
            const double aspect = double(o.width) / double(o.height);
            const double step = world->description().step;
            std::vector<Image> frames(ms.size());
            int tick = 0;
            const int total = int(o.starts.size()) * (o.frames + 2);
            for (double start : o.starts)
                for (int f = -2; f < o.frames; ++f, ++tick) {
                    const FrameContext& now = world->step();
                    const Camera camera = world->camera().at(start + step * (f + 2), aspect);
                    const bool measureError = withReference && f >= 0 && f % o.errorEvery == 0;
                    std::uint64_t digest = 0;
                    for (std::size_t i = 0; i < ms.size(); ++i) {
                        Method& m = ms[(i + std::size_t(tick)) % ms.size()];  // methods take turns going first
                        if (m.allocator) {
                            m.settings = m.allocator->ladder()[std::size_t(m.rung)].settings;
                            apply(*m.processor, *m.draw, m.settings, hysteresis, caches);
                        }
                        world->setTownLodScale(m.settings.townLodScale > 0.0 ? m.settings.townLodScale : townLodScale);
                        const ActorFrameStatistics s = m.processor->processFrame(world->root(), camera, now.time);
                        const std::uint64_t d = bench::stateDigest(world->crowd());
                        if (i == 0) digest = d;
                        else if (d != digest) fail("'" + m.name + "' saw another state");
                        Stopwatch watch;
                        m.draw->drawFrame(camera, m.processor->drawList());
                        const double cost = s.appCullMs() + watch.elapsedMs();
                        if (m.allocator) {
                            const int used = m.rung;
                            m.rung = m.allocator->observe(used, cost);
                            if (f >= 0) m.histogram[std::size_t(used)]++;
                            if (f >= 0) m.within += cost <= m.allocator->options().budgetMs ? 1 : 0;
                        }
                        if (f < 0) continue;
                        m.ms += cost;
                        m.frames += 1;
                        if (measureError) frames[std::size_t(&m - ms.data())] = m.draw->readFrame();
                    }
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
                    std::fprintf(stderr, "\rbench_budget: %s: tick %d/%d   ", what, tick + 1, total);
                }
            std::fprintf(stderr, "\n");
            for (Method& m : ms) {
                m.ms /= std::max(m.frames, 1.0);
                if (m.images > 0) m.psnr /= m.images, m.ssim /= m.images, m.off8 /= m.images;
            }
        };
        for (int f = 0; f < o.warmup; ++f) world->step();
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

        char line[1024];
        if (fixedCount > 0) report << "### " << world->crowd().size() << " actors, " << o.frames << " frames from each of " << o.starts.size()
               << " points of the camera path, " << o.width << "x" << o.height << "\n\n"
                                   << "| rung | APP+CULL+DRAW ms | PSNR dB | SSIM | pixels off > 8 | on the ladder |\n|---|---:|---:|---:|---:|---|\n";
        for (std::size_t i = 0; i < fixedCount; ++i) {
            const Method& m = methods[i];
            const auto at = std::find(front.begin(), front.end(), i);
            std::snprintf(line, sizeof line, "| %s | %.1f | %.2f | %.4f | %.2f %% | %s |\n", m.name.c_str(), m.ms, m.psnr, m.ssim, 100.0 * m.off8,
                          at == front.end() ? "no (dominated)" : ("rung " + std::to_string(at - front.begin())).c_str());
            report << line;
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
                rec.scene = sim::sceneName(o.scene);
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
            report << "\n| budget | allocator: within budget | mean ms | PSNR dB | SSIM | pixels off > 8 | rungs used | best fixed rung not dearer | its mean ms | PSNR dB | SSIM | pixels off > 8 |\n"
                      "|---:|---:|---:|---:|---:|---:|---|---|---:|---:|---:|---:|\n";
            for (std::size_t a = fixed; a < second.size(); ++a) {
                const Method& m = second[a];
                const Method* best = nullptr;
                for (std::size_t i = 0; i < fixed && !best; ++i)
                    if (second[i].ms <= m.ms) best = &second[i];
                std::string used;
                for (std::size_t r = 0; r < m.histogram.size(); ++r)
                    if (m.histogram[r]) used += (used.empty() ? "" : ", ") + std::to_string(r) + ": " + std::to_string(m.histogram[r]);
                std::snprintf(line, sizeof line, "| %.0f | %.1f %% | %.1f | %.2f | %.4f | %.2f %% | %s | %s | %s | %s | %s | %s |\n",
                              m.allocator->options().budgetMs, 100.0 * m.within / std::max(m.frames, 1.0), m.ms, m.psnr, m.ssim, 100.0 * m.off8,
                              used.c_str(), best ? best->name.c_str() : "none (every rung dearer)",
                              best ? std::to_string(best->ms).substr(0, 6).c_str() : "-", best ? std::to_string(best->psnr).substr(0, 5).c_str() : "-",
                              best ? std::to_string(best->ssim).substr(0, 6).c_str() : "-",
                              best ? (std::to_string(100.0 * best->off8).substr(0, 5) + " %").c_str() : "-");
                report << line;
            }
            report << "\nFixed rungs on the same ticks:\n\n| rung | APP+CULL+DRAW ms | PSNR dB | SSIM | pixels off > 8 |\n|---|---:|---:|---:|---:|\n";
            for (std::size_t i = 0; i < fixed; ++i) {
                std::snprintf(line, sizeof line, "| %s | %.1f | %.2f | %.4f | %.2f %% |\n", second[i].name.c_str(), second[i].ms, second[i].psnr,
                              second[i].ssim, 100.0 * second[i].off8);
                report << line;
            }
        }
    } catch (const std::exception& e) {
        fail(e.what());
    }
    std::fputs(report.str().c_str(), stdout);
    if (!o.markdown.empty()) {
        std::ofstream md(o.markdown);
        if (!md) fail("cannot write " + o.markdown);
        md << report.str();
    }
    return 0;
}
