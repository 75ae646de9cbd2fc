// bench_avoidance: avoidance quality as a measured knob. The same walkers (scene, seed, actor count)
// are stepped for the same ticks once per avoidance setting (the model, DetourCrowd or ORCA; for
// DetourCrowd its velocity sampling, 0 coarsest to 3 finest; how far agents look for neighbours); for each: the shared step's time,
// contacts per agent-second (two walkers coming into contact: centres closer than two radii and
// 5 cm, as test Avoidance.* counts it), the share of time walkers spend in contact, overlaps per
// agent-second (centres closer than two radii less 5 cm: DetourCrowd pushes overlaps apart after
// each move, so these are the collisions avoidance failed to prevent), progress towards their destinations, and how far their paths
// deviate from the finest setting's, tick by tick. --far-every adds the update rate of regions far
// from the camera path (effects.farUpdate) as a third axis.
//
//   bench_avoidance [--actors N] [--warmup N] [--ticks N] [--models detour,orca] [--qualities 0,1,2,3] [--ranges 6,12] [--threads N]
//                   [--far-every 1,4] [--far-distance M] [--markdown FILE] [--accuracy-csv FILE]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <glm/geometric.hpp>

#include "throng/bench/Experiment.h"
#include "throng/bench/ResultTable.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/sim/AccuracyCsv.h"
#include "throng/testkit/Assets.h"

namespace throng {
namespace {

// The experiment's own settings (the common ones are in bench::ExperimentSpec).
struct Options {
    std::vector<std::string> models{"detour"};
    std::vector<int> qualities{0, 1, 2, 3};
    std::vector<double> ranges{6.0, 12.0};
    std::vector<int> farEvery{1};
    double farDistance = 60.0;
};

struct Setting {
    std::string model = "detour";
    int quality = 3;  // DetourCrowd's sampling (ORCA has none)
    double range = 12.0;
    int farEvery = 1;  // far regions step every N steps (1: every region every step)
};

struct Result {
    Setting setting;
    double stepMs = 0;          // mean shared step
    double walkMs = 0;          // of which the walkers' own step (Locomotion)
    double stepBytes = 0;       // bytes the walkers' step holds per walker, after the last tick
    double collisions = 0;      // new contacts per agent-second
    double contact = 0;         // pair-seconds in contact per agent-second
    double overlaps = 0;        // new overlaps (centres closer than two radii less 5 cm) per agent-second
    double progress = 0;        // m/s towards the current destination, mean over agents
    double deviation = 0;       // m from the reference path, mean over agents and ticks
    double finalDeviation = 0;  // m, mean over agents at the last tick
    double ghosts = 0;          // mean ghosts per step
    double deferred = 0;        // mean walkers of far regions waiting per step
    std::size_t walkers = 0;
};

// Pairs of walkers closer than `reach` (metres, on the ground) into `out`, and of those the ones
// closer than `inner` into `innerOut`, as keys i * n + j with i < j.
void closePairs(const std::vector<glm::vec3>& p, float reach, float inner, std::unordered_set<std::uint64_t>& out,
                std::unordered_set<std::uint64_t>& innerOut) {
    out.clear();
    innerOut.clear();
    const auto cellOf = [reach](float v) { return static_cast<std::int64_t>(std::floor(v / reach)); };
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
    const auto key = [](std::int64_t x, std::int64_t z) { return (static_cast<std::uint64_t>(x) << 32) ^ static_cast<std::uint32_t>(z); };
    for (std::uint32_t i = 0; i < p.size(); ++i) grid[key(cellOf(p[i].x), cellOf(p[i].z))].push_back(i);
    const std::uint64_t n = p.size();
    for (std::uint32_t i = 0; i < p.size(); ++i) {
        const std::int64_t cx = cellOf(p[i].x), cz = cellOf(p[i].z);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dz = -1; dz <= 1; ++dz) {
                const auto it = grid.find(key(cx + dx, cz + dz));
                if (it == grid.end()) continue;
                for (std::uint32_t j : it->second) {
                    if (j <= i) continue;
                    const float ddx = p[i].x - p[j].x, ddz = p[i].z - p[j].z;
                    const float d2 = ddx * ddx + ddz * ddz;
                    if (d2 < reach * reach) out.insert(i * n + j);
                    if (d2 < inner * inner) innerOut.insert(i * n + j);
                }
            }
    }
}

// "ORCA", or DetourCrowd's model and sampling quality.
std::string label(const Setting& s) { return s.model == "orca" ? "ORCA" : "DetourCrowd, quality " + std::to_string(s.quality); }

// Steps the scene's walkers with `setting`; `reference` holds the finest setting's positions per
// tick (filled when empty).
Result run(const bench::ExperimentSpec& e, const Options& o, const Setting& setting, std::vector<std::vector<glm::vec3>>& reference) {
    sim::SceneDescription d = sim::parseSceneFile(e.scene);
    if (e.actors.front() > 0) sim::scaleActors(d, e.actors.front());
    d.effects.avoidance = true;
    d.effects.avoidanceModel = setting.model;
    d.effects.avoidanceQuality = setting.quality;
    d.effects.avoidanceRange = setting.range;
    d.effects.farUpdateEvery = setting.farEvery;
    d.effects.farUpdateDistance = setting.farEvery > 1 ? o.farDistance : 0.0;
    auto world = sim::Simulation::build(std::move(d));
    world->setThreads(static_cast<unsigned>(e.threads));
    const sim::Locomotion* walk = world->locomotion();
    if (!walk || walk->size() < 2) throw std::runtime_error("the scene has fewer than two walkers");
    const std::size_t n = walk->size();
    const float reach = 2.0f * walk->settings().radius + 0.05f;
    const bool fill = reference.empty();
    Result r;
    r.setting = setting;
    r.walkers = n;
    std::vector<glm::vec3> pos(n), lastPos(n), lastTarget(n);
    std::unordered_set<std::uint64_t> before, now, overlapBefore, overlapNow;
    std::uint64_t overlaps = 0;
    double progress = 0, deviation = 0, seconds = 0;
    std::uint64_t collisions = 0;
    // The first steps are not measured: walkers leave their start places and find their pace.
    const int total = e.warmup + e.frames;
    for (int t = 0; t < total; ++t) {
        const double dt = world->step().deltaTime;
        const bool measured = t >= e.warmup, since = t > e.warmup;  // since: a measured step before this one
        if (measured)
            r.stepMs += world->lastStepMs(), r.walkMs += walk->lastAdvanceMs(), r.ghosts += static_cast<double>(walk->lastGhostCount()),
                r.deferred += static_cast<double>(walk->lastDeferredCount());
        for (std::uint32_t s = 0; s < n; ++s) pos[s] = walk->position(s);
        closePairs(pos, reach, reach - 0.1f, now, overlapNow);
        if (since)
            for (std::uint64_t pair : now) collisions += before.count(pair) == 0;
        std::swap(before, now);
        if (since)
            for (std::uint64_t pair : overlapNow) overlaps += overlapBefore.count(pair) == 0;
        std::swap(overlapBefore, overlapNow);
        if (since) {
            seconds += dt;
            r.contact += static_cast<double>(before.size()) * dt;
            for (std::uint32_t s = 0; s < n; ++s) {
                if (walk->destination(s) != lastTarget[s]) continue;  // a new destination: no progress measured
                const glm::vec2 to(lastTarget[s].x, lastTarget[s].z);
                progress += glm::distance(glm::vec2(lastPos[s].x, lastPos[s].z), to) - glm::distance(glm::vec2(pos[s].x, pos[s].z), to);
            }
        }
        for (std::uint32_t s = 0; s < n; ++s) lastPos[s] = pos[s], lastTarget[s] = walk->destination(s);
        if (fill) reference.push_back(pos);
        double sum = 0;
        for (std::uint32_t s = 0; s < n; ++s) {
            const glm::vec3 ref = reference[static_cast<std::size_t>(t)][s];
            sum += glm::distance(glm::vec2(pos[s].x, pos[s].z), glm::vec2(ref.x, ref.z));
        }
        if (measured) deviation += sum / static_cast<double>(n);
        if (t == total - 1) r.finalDeviation = sum / static_cast<double>(n);
    }
    r.stepMs /= e.frames;
    r.stepBytes = double(walk->stepBytes()) / double(n);
    r.walkMs /= e.frames;
    r.ghosts /= e.frames;
    r.deferred /= e.frames;
    r.deviation = deviation / e.frames;
    r.overlaps = seconds > 0 ? static_cast<double>(overlaps) / (static_cast<double>(n) * seconds) : 0.0;
    r.contact = seconds > 0 ? r.contact / (static_cast<double>(n) * seconds) : 0.0;
    r.collisions = seconds > 0 ? static_cast<double>(collisions) / (static_cast<double>(n) * seconds) : 0.0;
    r.progress = seconds > 0 ? progress / (static_cast<double>(n) * seconds) : 0.0;
    std::fprintf(stderr, "bench_avoidance: %s, range %.0f, far regions every %d: done\n", label(setting).c_str(), setting.range,
                 setting.farEvery);
    return r;
}

bench::ResultTable table(const std::vector<Result>& rows) {
    bench::ResultTable t({{"", "avoidance", "%s"},
                          {"", "neighbour range (radii)", "%.0f"},
                          {"", "far regions step every", "%lld"},
                          {"", "walkers deferred", "%.0f"},
                          {"", "walkers", "%lld"},
                          {"", "step ms", "%.2f"},
                          {"", "walkers ms", "%.2f"},
                          {"", "step bytes per walker", "%.0f"},
                          {"", "vs finest", "%.2fx"},
                          {"", "contacts per agent-second", "%.4f"},
                          {"", "contact s per agent-second", "%.4f"},
                          {"", "overlaps per agent-second", "%.4f"},
                          {"", "progress m/s", "%.3f"},
                          {"", "path deviation m (mean)", "%.3f"},
                          {"", "at the last tick", "%.3f"},
                          {"", "ghosts per step", "%.0f"}});
    const double finest = rows.front().stepMs;
    for (const Result& r : rows)
        t.add({label(r.setting), r.setting.range, std::int64_t(r.setting.farEvery), r.deferred, std::int64_t(r.walkers), r.stepMs,
               r.walkMs, r.stepBytes, r.stepMs / finest, r.collisions, r.contact, r.overlaps, r.progress, r.deviation, r.finalDeviation, r.ghosts});
    return t;
}

}  // namespace
}  // namespace throng

int main(int argc, char** argv) {
    using namespace throng;
    Options o;
    bench::Experiment experiment("bench_avoidance",
                                 "Avoidance quality against step time: the same walkers stepped with each setting of DetourCrowd's "
                                 "velocity sampling and neighbour range; collisions, progress and path deviation from the finest.",
                                 bench::kScene | bench::kActorCount | bench::kFrames | bench::kWarmup | bench::kThreads | bench::kMarkdown |
                                     bench::kAccuracyCsv,
                                 {.scene = testkit::townDefaultScene(), .actors = {2000}, .frames = 300, .warmup = 30},
                                 {.frames = "--ticks", .framesHelp = "measured steps per setting", .minFrames = 2});
    CLI::App& app = experiment.app();
    app.add_option("--models", o.models, "avoidance models: detour (DetourCrowd) and orca")->delimiter(',')->type_name("M,M,...")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(CLI::IsMember({"detour", "orca"}));
    app.add_option("--qualities", o.qualities, "DetourCrowd's avoidance qualities (0 coarsest to 3 finest)")->delimiter(',')->type_name("Q,Q,...")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(CLI::Range(0, 3));
    app.add_option("--ranges", o.ranges, "neighbour ranges, agent radii (at least 1)")->delimiter(',')->type_name("R,R,...")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(bench::finiteNumber(1.0, 1000.0));
    app.add_option("--far-every", o.farEvery, "far regions step every N steps (1: every step)")->delimiter(',')->type_name("N,N,...")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(CLI::Range(1, 1000));
    app.add_option("--far-distance", o.farDistance, "regions farther than this from the camera path are far, metres")
        ->type_name("M")->check(bench::finiteNumber(1.0, 1e6));
    if (const auto code = experiment.parse(argc, argv)) return *code;
    const bench::ExperimentSpec& e = experiment.spec();
    std::vector<Result> rows;
    try {
        // The finest setting first: it is the reference the others deviate from.
        // (DetourCrowd's when it is measured, else ORCA's at the widest range.)
        const double widest = *std::max_element(o.ranges.begin(), o.ranges.end());
        const bool detour = std::find(o.models.begin(), o.models.end(), "detour") != o.models.end();
        std::vector<Setting> settings{{detour ? "detour" : "orca", 3, widest, 1}};
        const auto add = [&](const Setting& s) {
            if (!(s.model == settings[0].model && s.quality == settings[0].quality && s.range == settings[0].range && s.farEvery == 1))
                settings.push_back(s);
        };
        for (const std::string& model : o.models)
            for (int every : o.farEvery)
                for (double range : o.ranges) {
                    if (model == "orca") add({model, 3, range, every});
                    else
                        for (int q : o.qualities) add({model, q, range, every});
                }
        std::vector<std::vector<glm::vec3>> reference;
        for (const Setting& s : settings) rows.push_back(run(e, o, s, reference));
    } catch (const std::exception& ex) {
        experiment.fail(ex.what());
    }
    std::ostringstream report;
    report << "### Avoidance: " << rows.front().walkers << " walkers, " << e.frames << " steps after " << e.warmup << ", " << e.threads
           << " thread(s); deviation from " << label(rows.front().setting) << " at the widest range\n\n"
           << table(rows).markdown() << "\n";
    std::fputs(report.str().c_str(), stdout);
    try {
        if (!e.markdown.empty()) bench::writeWhole(e.markdown, report.str());
    } catch (const std::exception& ex) {
        experiment.fail(ex.what());
    }
    if (!e.accuracyCsv.empty()) {
        // The common accuracy CSV: the finest setting (the first row, the reference) is "off"; path
        // deviation from it comes first, the measure that is zero there by construction.
        try {
            sim::AccuracyCsv csv(e.accuracyCsv);
            for (const Result& r : rows) {
                sim::AccuracyRecord a;
                a.knob = r.setting.farEvery > 1 ? "avoidance quality and far update" : "avoidance quality";
                std::ostringstream value;
                value << (r.setting.model == "orca" ? std::string("orca") : std::to_string(r.setting.quality)) << " at range " << r.setting.range;
                if (r.setting.farEvery > 1) value << ", far every " << r.setting.farEvery;
                a.value = value.str();
                a.off = &r == &rows.front();
                a.metrics = {{"path_deviation", r.deviation, "m", true},
                             {"contacts", r.collisions, "1/(agent s)", true},
                             {"contact_time", r.contact, "pair s/(agent s)", true},
                             {"overlaps", r.overlaps, "1/(agent s)", true},
                             {"progress", r.progress, "m/s", false}};
                a.ms = r.stepMs;
                a.msPhase = "step";
                a.scene = sim::sceneName(e.scene);
                a.camera = "none";
                a.actors = std::int64_t(r.walkers);
                csv.add(a);
            }
        } catch (const std::exception& ex) {
            experiment.fail(ex.what());
        }
    }
    return 0;
}
