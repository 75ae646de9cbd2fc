// bench_ranks: the shared step split over the ranks of an MPI run. Run it plainly (one process,
// with 1 or 2 threads) and under `mpirun -np N` (each rank steps its share of the walkers'
// regions, rank 0 gathers every walker): the same scene, seed and steps, so the rows compare. For
// each actor count rank 0 reports the wall time of a step (its own step, which waits for the
// other ranks' walkers), each rank's work and wait, and what crossed between ranks: ghost and
// handover records with their bytes, and the walkers' state sent to rank 0.
//
//   bench_ranks [--actors N,N,...] [--region-blocks B] [--warmup N] [--steps N] [--threads N] [--csv FILE]
//               [--avoidance-quality Q] [--avoidance-range R] [--far-every N] [--far-distance M]
//
// --csv appends (a header first when the file is new), so plain and mpirun runs collect in one file.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "throng/bench/Experiment.h"
#include "throng/bench/ResultTable.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/Ranks.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/testkit/Assets.h"

namespace throng {
namespace {

// The experiment's own settings (the common ones are in bench::ExperimentSpec).
struct Options {
    int regionBlocks = 0;  // regions of B x B blocks instead of the scene's (0: the scene's)
    int quality = -1;      // avoidance quality instead of the scene's (-1: the scene's)
    double range = 0.0;    // avoidance range in radii instead of the scene's (0: the scene's)
    int farEvery = 1;      // far regions step every N steps (1: the scene's setting)
    double farDistance = 60.0;
};

// One actor count's means per measured step (on rank 0, over every rank where it says so).
struct Row {
    std::int64_t actors = 0;
    std::size_t walkers = 0, regions = 0;
    double buildSeconds = 0, stepMs = 0, peakGb = 0;
    std::vector<double> workMs, waitMs, agents;     // per rank
    std::vector<double> stepping;                   // per rank: walkers whose region stepped (far ones may wait)
    double ghosts = 0, ghostsToRanks = 0, handedToRanks = 0, borderBytes = 0, stateBytes = 0;
};

double peakMemoryGb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / (1024.0 * 1024.0);
}

Row measure(const bench::ExperimentSpec& e, const Options& o, std::int64_t actors, sim::Ranks& ranks) {
    Row row;
    row.actors = actors;
    sim::SceneDescription d = sim::parseSceneFile(e.scene);
    sim::scaleActors(d, actors);
    if (o.regionBlocks > 0 && d.town) d.town->regions.clear(), d.town->regionBlocks = {o.regionBlocks, o.regionBlocks};
    if (o.quality >= 0) d.effects.avoidanceQuality = o.quality;
    if (o.range > 0.0) d.effects.avoidanceRange = o.range;
    if (o.farEvery > 1) d.effects.farUpdateEvery = o.farEvery, d.effects.farUpdateDistance = o.farDistance;
    const auto t0 = std::chrono::steady_clock::now();
    auto world = sim::Simulation::build(std::move(d));
    row.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!world->locomotion()) throw std::runtime_error("the scene has no walkers");
    if (sim::Ranks::launchedByMpi()) world->distribute(ranks);
    world->setThreads(unsigned(e.threads));
    const sim::Locomotion& walk = *world->locomotion();
    row.walkers = walk.size();
    row.regions = walk.regionCount();
    for (int s = 0; s < e.warmup; ++s) world->step();
    const auto n = walk.distributed() ? std::size_t(ranks.size()) : 0;
    row.workMs.assign(n, 0.0), row.waitMs.assign(n, 0.0), row.agents.assign(n, 0.0), row.stepping.assign(n, 0.0);
    for (int s = 0; s < e.frames; ++s) {
        world->step();
        row.stepMs += world->lastStepMs() / e.frames;
        row.ghosts += double(walk.lastGhostCount()) / e.frames;
        for (std::size_t r = 0; r < walk.rankSteps().size(); ++r) {
            const auto& share = walk.rankSteps()[r];
            row.workMs[r] += share.workMs / e.frames, row.waitMs[r] += share.waitMs / e.frames;
            row.agents[r] += double(share.agents) / e.frames;
            row.stepping[r] += double(share.agents - share.deferred) / e.frames;
            row.ghostsToRanks += double(share.ghostsToRanks) / e.frames, row.handedToRanks += double(share.handedToRanks) / e.frames;
            row.borderBytes += double(share.borderBytes) / e.frames, row.stateBytes += double(share.stateBytes) / e.frames;
        }
    }
    row.peakGb = peakMemoryGb();
    return row;
}

std::string join(const std::vector<double>& values, const char* format) {
    std::string out;
    char cell[64];
    for (double v : values) {
        std::snprintf(cell, sizeof cell, format, v);
        out += (out.empty() ? "" : " / ") + std::string(cell);
    }
    return out.empty() ? "-" : out;
}

}  // namespace
}  // namespace throng

int main(int argc, char** argv) {
    using namespace throng;
    Options o;
    bench::Experiment experiment("bench_ranks",
                                 "The shared step split over MPI ranks: run plainly and under mpirun -np N on the same scene; "
                                 "step time, each rank's work and wait, and the bytes exchanged per border agent.",
                                 bench::kScene | bench::kActorList | bench::kFrames | bench::kWarmup | bench::kThreads | bench::kCsv,
                                 {.scene = testkit::townDefaultScene(), .actors = {10000, 100000}, .frames = 20, .warmup = 10},
                                 {.frames = "--steps", .framesHelp = "measured steps", .minActors = 2, .maxActors = 2'000'000,
                                  .csvHelp = "append the rows to this CSV (a header first when it is new)"});
    CLI::App& app = experiment.app();
    app.add_option("--region-blocks", o.regionBlocks, "regions of B x B city blocks instead of the scene's")->type_name("B")->check(CLI::Range(1, 1000));
    app.add_option("--avoidance-quality", o.quality, "avoidance quality instead of the scene's (0 coarsest to 3)")->type_name("Q")->check(CLI::Range(0, 3));
    app.add_option("--avoidance-range", o.range, "avoidance range, agent radii, instead of the scene's")->type_name("R")->check(bench::finiteNumber(1.0, 1000.0));
    app.add_option("--far-every", o.farEvery, "regions far from the camera path step every N steps")->type_name("N")->check(CLI::Range(1, 1000));
    app.add_option("--far-distance", o.farDistance, "with --far-every: regions beyond M metres are far")->type_name("M")->check(bench::finiteNumber(1.0, 1e6));
    if (const auto code = experiment.parse(argc, argv)) return *code;
    const bench::ExperimentSpec& e = experiment.spec();
    sim::Ranks ranks(std::chrono::minutes(10));  // building a million actors takes minutes, not the same on every rank
    const bool first = ranks.rank() == 0;
    bench::ResultTable table({{"actors", "actors", "%lld"},
                              {"walkers", "walkers", "%lld"},
                              {"regions", "regions", "%lld"},
                              {"ranks", "", "%lld"},
                              {"threads", "", "%lld"},
                              {"", "ranks x threads", "%s", true},
                              {"step_ms", "step ms", "%.1f"},
                              {"", "work ms per rank", "%s", true},
                              {"max_work_ms", "", "%g"},
                              {"", "wait ms per rank", "%s", true},
                              {"max_wait_ms", "", "%g"},
                              {"", "walkers per rank", "%s", true},
                              {"", "stepping per rank", "%s", true},
                              {"ghosts", "ghosts", "%.0f"},
                              {"ghosts_to_ranks", "to other ranks", "%.0f"},
                              {"handed_to_ranks", "handed to other ranks", "%.1f"},
                              {"border_bytes", "border bytes", "%.0f"},
                              {"", "bytes per border agent", "%s"},
                              {"state_bytes", "state bytes to rank 0", "%.0f"},
                              {"build_s", "build s", "%.1f"},
                              {"peak_gb", "peak GB (rank 0)", "%.2f"}});
    for (std::int64_t actors : e.actors) {
        Row r;
        try {
            r = measure(e, o, actors, ranks);
        } catch (const std::exception& ex) {
            std::fprintf(stderr, "bench_ranks%s: %lld actors: %s\n", ranks.size() > 1 ? (" (rank " + std::to_string(ranks.rank()) + ")").c_str() : "",
                         (long long)actors, ex.what());
            ranks.abort(1);
        }
        if (!first) continue;
        const double borderAgents = r.ghostsToRanks + r.handedToRanks;
        const auto most = [](const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); };
        table.add({r.actors, std::int64_t(r.walkers), std::int64_t(r.regions), std::int64_t(ranks.size()), std::int64_t(e.threads),
                   std::to_string(ranks.size()) + " x " + std::to_string(e.threads), r.stepMs, join(r.workMs, "%.1f"), most(r.workMs),
                   join(r.waitMs, "%.1f"), most(r.waitMs), join(r.agents, "%.0f"), join(r.stepping, "%.0f"), r.ghosts, r.ghostsToRanks,
                   r.handedToRanks, r.borderBytes, borderAgents > 0 ? std::to_string(int(r.borderBytes / borderAgents + 0.5)) : "-",
                   r.stateBytes, r.buildSeconds, r.peakGb});
        experiment.progress(std::to_string(actors) + " actors measured");
    }
    if (!first) return 0;
    std::fputs(table.markdown().c_str(), stdout);
    if (!e.csv.empty()) {
        const bool fresh = !std::filesystem::exists(e.csv);
        std::ofstream csv(e.csv, std::ios::app);
        csv << (fresh ? table.csvHeader() : "") << table.csvRows();
        if (!csv) experiment.fail("cannot write " + e.csv);
    }
    return 0;
}
