// bench_avoidance: avoidance quality as a measured knob. The same walkers (scene, seed, actor count)
// are stepped for the same ticks once per avoidance setting (DetourCrowd's velocity sampling, 0
// coarsest to 3 finest, and how far agents look for neighbours); for each: the shared step's time,
// contacts per agent-second (two walkers coming into contact: centres closer than two radii and
// 5 cm, as test Avoidance.* counts it), the share of time walkers spend in contact, overlaps per
// agent-second (centres closer than two radii less 5 cm: DetourCrowd pushes overlaps apart after
// each move, so these are the collisions avoidance failed to prevent), progress towards their destinations, and how far their paths
// deviate from the finest setting's, tick by tick. --far-every adds the update rate of regions far
// from the camera path (effects.farUpdate) as a third axis.
//
//   bench_avoidance [--actors N] [--warmup N] [--ticks N] [--qualities 0,1,2,3] [--ranges 6,12] [--threads N]
//                   [--far-every 1,4] [--far-distance M] [--markdown FILE] [--accuracy-csv FILE]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <glm/geometric.hpp>

#include "throng/testkit/Assets.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/sim/AccuracyCsv.h"
#include "throng/support/CommandLine.h"
#include "throng/support/Validators.h"

namespace throng {
namespace {

[[noreturn]] void fail(const std::string& why) {
    std::fprintf(stderr, "bench_avoidance: %s\n", why.c_str());
    std::exit(1);
}

struct Options {
    std::string scene = testkit::townDefaultScene();
    std::int64_t actors = 2000;
    int ticks = 300;
    int warmup = 30;
    int threads = 1;
    std::vector<int> qualities{0, 1, 2, 3};
    std::vector<double> ranges{6.0, 12.0};
    std::vector<int> farEvery{1};
    double farDistance = 60.0;
    std::string markdown, accuracyCsv;
};

struct Setting {
    int quality = 3;
    double range = 12.0;
    int farEvery = 1;  // far regions step every N steps (1: every region every step)
};

struct Result {
    Setting setting;
    double stepMs = 0;          // mean shared step
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

// Steps the scene's walkers with `setting`; `reference` holds the finest setting's positions per
// tick (filled when empty).
Result run(const Options& o, const Setting& setting, std::vector<std::vector<glm::vec3>>& reference) {
    sim::SceneDescription d = sim::parseSceneFile(o.scene);
    if (o.actors > 0) sim::scaleActors(d, o.actors);
    d.effects.avoidance = true;
    d.effects.avoidanceQuality = setting.quality;
    d.effects.avoidanceRange = setting.range;
    d.effects.farUpdateEvery = setting.farEvery;
    d.effects.farUpdateDistance = setting.farEvery > 1 ? o.farDistance : 0.0;
    auto world = sim::Simulation::build(std::move(d));
    world->setThreads(static_cast<unsigned>(o.threads));
    const sim::Locomotion* walk = world->locomotion();
    if (!walk || walk->size() < 2) fail("the scene has fewer than two walkers");
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
    const int total = o.warmup + o.ticks;
    for (int t = 0; t < total; ++t) {
        const double dt = world->step().deltaTime;
        const bool measured = t >= o.warmup, since = t > o.warmup;  // since: a measured step before this one
        if (measured)
            r.stepMs += world->lastStepMs(), r.ghosts += static_cast<double>(walk->lastGhostCount()),
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
    r.stepMs /= o.ticks;
    r.ghosts /= o.ticks;
    r.deferred /= o.ticks;
    r.deviation = deviation / o.ticks;
    r.overlaps = seconds > 0 ? static_cast<double>(overlaps) / (static_cast<double>(n) * seconds) : 0.0;
    r.contact = seconds > 0 ? r.contact / (static_cast<double>(n) * seconds) : 0.0;
    r.collisions = seconds > 0 ? static_cast<double>(collisions) / (static_cast<double>(n) * seconds) : 0.0;
    r.progress = seconds > 0 ? progress / (static_cast<double>(n) * seconds) : 0.0;
    std::fprintf(stderr, "bench_avoidance: quality %d, range %.0f, far regions every %d: done\n", setting.quality, setting.range,
                 setting.farEvery);
    return r;
}

std::string table(const std::vector<Result>& rows) {
    std::ostringstream t;
    char line[512];
    t << "| quality | neighbour range (radii) | far regions step every | walkers deferred | walkers | step ms | vs finest | contacts per agent-second | contact s per agent-second | overlaps per agent-second | "
         "progress m/s | path deviation m (mean) | at the last tick | ghosts per step |\n"
         "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    const double finest = rows.front().stepMs;
    for (const Result& r : rows) {
        std::snprintf(line, sizeof line, "| %d | %.0f | %d | %.0f | %zu | %.2f | %.2fx | %.4f | %.4f | %.4f | %.3f | %.3f | %.3f | %.0f |\n", r.setting.quality,
                      r.setting.range, r.setting.farEvery, r.deferred, r.walkers, r.stepMs, r.stepMs / finest, r.collisions, r.contact, r.overlaps, r.progress, r.deviation, r.finalDeviation, r.ghosts);
        t << line;
    }
    return t.str();
}

}  // namespace
}  // namespace throng

int main(int argc, char** argv) {
    using namespace throng;
    using support::wholeNumber;
    Options o;
    support::CommandLine cl("bench_avoidance",
                            "Avoidance quality against step time: the same walkers stepped with each setting of DetourCrowd's "
                            "velocity sampling and neighbour range; collisions, progress and path deviation from the finest.");
    CLI::App& app = cl.app();
    app.add_option("--scene", o.scene, "scene file")->type_name("FILE")->check(support::existingFile());
    app.add_option("--actors", o.actors, "actors (0: the scene's own count)")->type_name("N")->check(wholeNumber(0, 10'000'000))->capture_default_str();
    app.add_option("--warmup", o.warmup, "steps first, not measured")->type_name("N")->check(wholeNumber(0, 1'000'000))->capture_default_str();
    app.add_option("--ticks", o.ticks, "measured steps per setting")->type_name("N")->check(wholeNumber(2, 1'000'000))->capture_default_str();
    app.add_option("--threads", o.threads, "threads of the step")->type_name("N")->check(wholeNumber(1, 256))->capture_default_str();
    app.add_option("--qualities", o.qualities, "avoidance qualities (0 coarsest to 3 finest)")->delimiter(',')->type_name("Q,Q,...")
        ->check(wholeNumber(0, 3));
    app.add_option("--ranges", o.ranges, "neighbour ranges, agent radii (at least 1)")->delimiter(',')->type_name("R,R,...")
        ->check(CLI::Range(1.0, 1000.0));
    app.add_option("--far-every", o.farEvery, "far regions step every N steps (1: every step)")->delimiter(',')->type_name("N,N,...")
        ->check(wholeNumber(1, 1000));
    app.add_option("--far-distance", o.farDistance, "regions farther than this from the camera path are far, metres")
        ->type_name("M")->check(CLI::Range(1.0, 1e6))->capture_default_str();
    app.add_option("--markdown", o.markdown, "also write the table as Markdown")->type_name("FILE");
    app.add_option("--accuracy-csv", o.accuracyCsv, "write the rows in the common accuracy CSV")->type_name("FILE");
    if (const auto code = cl.parse(argc, argv)) return *code;
    std::vector<Result> rows;
    try {
        // The finest setting first: it is the reference the others deviate from.
        std::vector<Setting> settings{{3, *std::max_element(o.ranges.begin(), o.ranges.end()), 1}};
        for (int every : o.farEvery)
            for (double range : o.ranges)
                for (int q : o.qualities)
                    if (!(q == settings[0].quality && range == settings[0].range && every == 1)) settings.push_back({q, range, every});
        std::vector<std::vector<glm::vec3>> reference;
        for (const Setting& s : settings) rows.push_back(run(o, s, reference));
    } catch (const std::exception& e) {
        fail(e.what());
    }
    std::ostringstream report;
    report << "### Avoidance: " << rows.front().walkers << " walkers, " << o.ticks << " steps after " << o.warmup << ", " << o.threads
           << " thread(s); deviation from quality 3 at the widest range\n\n"
           << table(rows) << "\n";
    std::fputs(report.str().c_str(), stdout);
    if (!o.markdown.empty()) {
        std::ofstream md(o.markdown);
        if (!md) fail("cannot write " + o.markdown);
        md << report.str();
    }
    if (!o.accuracyCsv.empty()) {
        // The common accuracy CSV: the finest setting (the first row, the reference) is "off"; path
        // deviation from it comes first, the measure that is zero there by construction.
        try {
            sim::AccuracyCsv csv(o.accuracyCsv);
            for (const Result& r : rows) {
                sim::AccuracyRecord a;
                a.knob = r.setting.farEvery > 1 ? "avoidance quality and far update" : "avoidance quality";
                std::ostringstream value;
                value << r.setting.quality << " at range " << r.setting.range;
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
                a.scene = sim::sceneName(o.scene);
                a.camera = "none";
                a.actors = std::int64_t(r.walkers);
                csv.add(a);
            }
        } catch (const std::exception& e) {
            fail(e.what());
        }
    }
    return 0;
}
