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

#include "throng/testkit/Assets.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/Ranks.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/support/CommandLine.h"
#include "throng/support/Validators.h"

namespace throng {
namespace {

struct Options {
    std::string scene = testkit::townDefaultScene();
    std::vector<std::int64_t> actors{10000, 100000};
    int warmup = 10;
    int steps = 20;
    int threads = 1;
    int regionBlocks = 0;  // regions of B x B blocks instead of the scene's (0: the scene's)
    int quality = -1;      // avoidance quality instead of the scene's (-1: the scene's)
    double range = 0.0;    // avoidance range in radii instead of the scene's (0: the scene's)
    int farEvery = 1;      // far regions step every N steps (1: the scene's setting)
    double farDistance = 60.0;
    std::string csv;
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

Row measure(const Options& o, std::int64_t actors, sim::Ranks& ranks) {
    Row row;
    row.actors = actors;
    sim::SceneDescription d = sim::parseSceneFile(o.scene);
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
    world->setThreads(unsigned(o.threads));
    const sim::Locomotion& walk = *world->locomotion();
    row.walkers = walk.size();
    row.regions = walk.regionCount();
    for (int s = 0; s < o.warmup; ++s) world->step();
    const auto n = walk.distributed() ? std::size_t(ranks.size()) : 0;
    row.workMs.assign(n, 0.0), row.waitMs.assign(n, 0.0), row.agents.assign(n, 0.0), row.stepping.assign(n, 0.0);
    for (int s = 0; s < o.steps; ++s) {
        world->step();
        row.stepMs += world->lastStepMs() / o.steps;
        row.ghosts += double(walk.lastGhostCount()) / o.steps;
        for (std::size_t r = 0; r < walk.rankSteps().size(); ++r) {
            const auto& share = walk.rankSteps()[r];
            row.workMs[r] += share.workMs / o.steps, row.waitMs[r] += share.waitMs / o.steps;
            row.agents[r] += double(share.agents) / o.steps;
            row.stepping[r] += double(share.agents - share.deferred) / o.steps;
            row.ghostsToRanks += double(share.ghostsToRanks) / o.steps, row.handedToRanks += double(share.handedToRanks) / o.steps;
            row.borderBytes += double(share.borderBytes) / o.steps, row.stateBytes += double(share.stateBytes) / o.steps;
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
    support::CommandLine cl("bench_ranks",
                            "The shared step split over MPI ranks: run plainly and under mpirun -np N on the same scene; "
                            "step time, each rank's work and wait, and the bytes exchanged per border agent.");
    CLI::App& app = cl.app();
    app.add_option("--scene", o.scene, "scene file")->type_name("FILE")->check(support::existingFile());
    app.add_option("--actors", o.actors, "actor counts")->delimiter(',')->type_name("N,N,...")->check(support::wholeNumber(2, 2'000'000));
    app.add_option("--warmup", o.warmup, "steps first, not measured")->type_name("N")->check(support::wholeNumber(0, 100000))->capture_default_str();
    app.add_option("--steps", o.steps, "measured steps")->type_name("N")->check(support::wholeNumber(1, 100000))->capture_default_str();
    app.add_option("--threads", o.threads, "threads of each rank's step")->type_name("N")->check(support::wholeNumber(1, 256))->capture_default_str();
    app.add_option("--region-blocks", o.regionBlocks, "regions of B x B city blocks instead of the scene's")
        ->type_name("B")->check(support::wholeNumber(1, 1000));
    app.add_option("--avoidance-quality", o.quality, "avoidance quality instead of the scene's (0 coarsest to 3)")
        ->type_name("Q")->check(support::wholeNumber(0, 3));
    app.add_option("--avoidance-range", o.range, "avoidance range, agent radii, instead of the scene's")
        ->type_name("R")->check(CLI::Range(1.0, 1000.0));
    app.add_option("--far-every", o.farEvery, "regions far from the camera path step every N steps")
        ->type_name("N")->check(support::wholeNumber(1, 1000));
    app.add_option("--far-distance", o.farDistance, "with --far-every: regions beyond M metres are far")
        ->type_name("M")->check(CLI::Range(1.0, 1e6))->capture_default_str();
    app.add_option("--csv", o.csv, "append the rows to this CSV")->type_name("FILE");
    try {
        if (!cl.parseOrThrow(argc, argv)) {
            std::fputs(cl.help().c_str(), stdout);
            return 0;
        }
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "bench_ranks: %s\n%s", e.what(), support::CommandLine::hint("bench_ranks").c_str());
        return 2;
    }
    sim::Ranks ranks(std::chrono::minutes(10));  // building a million actors takes minutes, not the same on every rank
    const bool first = ranks.rank() == 0;
    if (first)
        std::printf("| actors | walkers | regions | ranks x threads | step ms | work ms per rank | wait ms per rank | walkers per rank | "
                    "stepping per rank | ghosts | to other ranks | handed to other ranks | border bytes | bytes per border agent | state bytes to rank 0 | "
                    "build s | peak GB (rank 0) |\n|---:|---:|---:|---|---:|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (std::int64_t actors : o.actors) {
        Row r;
        try {
            r = measure(o, actors, ranks);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "bench_ranks%s: %lld actors: %s\n", ranks.size() > 1 ? (" (rank " + std::to_string(ranks.rank()) + ")").c_str() : "",
                         (long long)actors, e.what());
            ranks.abort(1);
        }
        if (!first) continue;
        const double borderAgents = r.ghostsToRanks + r.handedToRanks;
        std::printf("| %lld | %zu | %zu | %d x %d | %.1f | %s | %s | %s | %s | %.0f | %.0f | %.1f | %.0f | %s | %.0f | %.1f | %.2f |\n", (long long)r.actors,
                    r.walkers, r.regions, ranks.size(), o.threads, r.stepMs, join(r.workMs, "%.1f").c_str(), join(r.waitMs, "%.1f").c_str(),
                    join(r.agents, "%.0f").c_str(), join(r.stepping, "%.0f").c_str(), r.ghosts, r.ghostsToRanks, r.handedToRanks, r.borderBytes,
                    borderAgents > 0 ? std::to_string(int(r.borderBytes / borderAgents + 0.5)).c_str() : "-", r.stateBytes, r.buildSeconds, r.peakGb);
        std::fflush(stdout);
        if (!o.csv.empty()) {
            const bool fresh = !std::filesystem::exists(o.csv);
            std::ofstream csv(o.csv, std::ios::app);
            if (fresh) csv << "actors,walkers,regions,ranks,threads,step_ms,max_work_ms,max_wait_ms,ghosts,ghosts_to_ranks,handed_to_ranks,border_bytes,state_bytes,build_s,peak_gb\n";
            csv << r.actors << ',' << r.walkers << ',' << r.regions << ',' << ranks.size() << ',' << o.threads << ',' << r.stepMs << ','
                << (r.workMs.empty() ? 0.0 : *std::max_element(r.workMs.begin(), r.workMs.end())) << ','
                << (r.waitMs.empty() ? 0.0 : *std::max_element(r.waitMs.begin(), r.waitMs.end())) << ',' << r.ghosts << ','
                << r.ghostsToRanks << ',' << r.handedToRanks << ',' << r.borderBytes << ',' << r.stateBytes << ',' << r.buildSeconds << ','
                << r.peakGb << '\n';
        }
    }
    return 0;
}
