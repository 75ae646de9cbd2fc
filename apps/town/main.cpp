// throng-town: the town-crowd example. Builds the world a scene file declares (a town of modular
// tiles, walkers on its navigation mesh, standing groups, a flock; far actors as impostors when the
// scene sets an impostor distance), then runs it: in a window when there is a display (free camera,
// pause, LOD scale, a shrunken culling pyramid to watch culling at work, on-screen statistics),
// headless otherwise (PNG frames every K frames, stats.csv per frame, summary.json, a progress bar).
//
// Every frame is: step (the simulation advances once), APP/CULL (the seven phases), DRAW (meshes,
// then impostors). With --pipeline on, DRAW of frame N runs while frame N+1 is stepped and culled,
// from frame N's own draw list; the frames written are the same either way.
//
// Under mpirun -np N every rank steps its share of the walkers' regions; rank 0 builds the whole
// world and sends the others its navigation mesh, from which they build only what stepping walkers
// needs (the walkers' templates and Locomotion).
// Rank 0 gathers the walkers near the frame's view after each step (the others cannot be seen),
// then culls, draws and writes as one process would (stats.csv adds each rank's share of the step
// and its peak memory). The files are the same with any number of ranks.
//
// With --frame-budget MS, a FrameBudgetAllocator picks each frame's rung of a ladder (LOD scale,
// impostor distance, key-pose distance, morph budget) from the APP+CULL+DRAW measured so far: a
// frame's cost is its APP+CULL (the processor's phases) plus its DRAW (beginFrame to endFrame), each
// timed on the thread that runs it; with --pipeline on they overlap the neighbouring frames' work
// (and share the cores with it), so a frame's cost is not the wall time between frames. The rung
// chosen after frame N's DRAW applies from the next frame prepared (N+2 pipelined, N+1 otherwise);
// a frame is processed and drawn with one rung, which stats.csv records.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <new>
#include <string>

#include "CrowdRecording.h"
#include "MemoryNeed.h"
#include "RankAgreement.h"
#include "RankPosing.h"
#include "RankWait.h"
#include "TownOptions.h"
#include "TownRun.h"
#include "throng/render/ContextFactory.h"
#include "throng/sim/BudgetLadder.h"
#include "throng/sim/FrameBudgetAllocator.h"
#include "throng/sim/Ranks.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneError.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/support/GlOption.h"
#include "throng/support/ProgressBar.h"
#include "throng/support/StopSignals.h"

using namespace throng;

namespace {

// " (rank N)" in messages of a run of several ranks.
std::string rankLabel(const sim::Ranks& ranks) { return ranks.size() > 1 ? " (rank " + std::to_string(ranks.rank()) + ")" : ""; }

// A rank other than 0: rank 0's navigation mesh (none when nothing walks), once rank 0 has built it.
std::shared_ptr<const sim::NavMesh> receiveNavMesh(sim::Ranks& ranks) {
    const sim::Bytes bytes = town::waitLong(ranks, [&] { return ranks.broadcast({}, town::kNavMeshTag, "navigation mesh"); });
    if (bytes.empty()) return nullptr;
    try {
        return sim::NavMesh::fromBytes(bytes);
    } catch (const std::invalid_argument& e) {
        throw sim::RankError(0, std::string("rank 0 sent a navigation mesh that cannot be read: ") + e.what());
    }
}

// A rank other than 0: waits for rank 0's set-up, then steps its share of the regions as often as
// rank 0 steps (once per frame), writing nothing. A failure stops every rank.
int stepShare(sim::Simulation& world, sim::Ranks& ranks, const town::TownOptions& o) {
    try {
        world.setThreads(unsigned(o.threads));
        town::waitLong(ranks, [&] { return ranks.broadcast({}, town::kStartTag, "start"); });  // baking impostors takes a while
        for (std::int64_t f = 0; f < o.frames; ++f) world.step();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-town%s: %s\n", rankLabel(ranks).c_str(), e.what());
        ranks.abort(3);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    support::StopSignals::install();  // SIGINT, SIGTERM: the frame in progress ends, the files are closed whole
    town::TownOptions o;
    sim::SceneDescription scene;
    std::unique_ptr<town::CrowdRecording> recorder;  // --vtk: crowd data for ParaView
    try {
        o = town::parseTownOptions(argc, argv, THRONG_TOWN_DEFAULT_SCENE, THRONG_TOWN_DEFAULT_LADDER);
        scene = sim::parseSceneFile(o.scene);
        if (o.actors) sim::scaleActors(scene, *o.actors);  // refuses a crowd the town cannot hold
        if (!o.looks)
            for (auto& [name, t] : scene.templates) t.looks.clear();
        if (!o.faces) scene.effects.faces.face = scene.effects.faces.blink = scene.effects.faces.phrase = false;
        // A crowd the machine cannot hold stops here, before allocating, not in the kernel's hands.
        if (const auto problem = town::memoryProblem(scene, town::availableMemory())) throw std::invalid_argument(*problem);
    } catch (const sim::SceneError& e) {
        std::fprintf(stderr, "throng-town: %s\n", e.what());
        return 2;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "throng-town: %s\n%s", e.what(), town::townUsage().c_str());
        return 2;
    }
    // --frame-budget: the ladder is read (and refused) before anything is built.
    std::unique_ptr<sim::FrameBudgetAllocator> budget;
    if (o.frameBudget > 0.0) try {
        sim::FrameBudgetOptions options;
        options.budgetMs = o.frameBudget;
        budget = std::make_unique<sim::FrameBudgetAllocator>(sim::readBudgetLadder(o.frameBudgetLadder), options);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-town: --frame-budget-ladder: %s\n%s", e.what(), town::townUsage().c_str());
        return 2;
    }
    // A headless context asked for by name is tried before minutes of building: one missing is a
    // one-line error, exit 2, as for a bad option.
    if (const auto code = support::refuseUnavailableGl("throng-town", o.gl)) return *code;
    // Started by mpirun, each rank steps its share of the walkers' regions (one rank alone too, so
    // that `mpirun -np 1` takes the distributed path); rank 0 draws and writes.
    sim::Ranks ranks(std::chrono::milliseconds(std::llround(o.rankTimeout * 1000.0)));
    const bool distributed = sim::Ranks::launchedByMpi();
    // Every rank reads its own scene file and command line (on two hosts, two copies): one whose
    // world would differ from rank 0's says what differs and stops the run before anything is built.
    if (ranks.size() > 1) try {
        const town::WorldKey mine = town::worldKey(o);
        const std::vector<town::WorldKey> root = sim::unpackRecords<town::WorldKey>(
            ranks.broadcast(sim::packRecords(std::span(&mine, 1)), town::kWorldKeyTag, "world key"), 0, "world key");
        if (root.size() != 1) throw sim::RankError(0, "rank 0 sent " + std::to_string(root.size()) + " world keys, not one");
        if (const auto problem = town::disagreement(mine, root[0], o.scene)) throw std::invalid_argument(*problem);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-town%s: %s\n", rankLabel(ranks).c_str(), e.what());
        ranks.abort(2);
    }
    // Only rank 0 writes, --vtk files too.
    if (!o.vtk.empty() && ranks.rank() == 0) try {
        recorder = town::openCrowdRecording(o.vtk, o.vtkEvery);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "throng-town: --vtk: %s\n%s", e.what(), town::townUsage().c_str());
        if (ranks.size() > 1) ranks.abort(2);
        return 2;
    }
    if (o.seed) scene.seed = *o.seed;
    if (budget && !(scene.town && !scene.town->lod.empty() && scene.town->lodScale > 0.0))
        for (std::size_t r = 0; r < budget->ladder().size(); ++r)
            if (budget->ladder()[r].settings.townLodScale > 0.0) {
                std::fprintf(stderr, "throng-town: --frame-budget: rung %zu sets town-lod-scale, but the scene declares no town LOD "
                                     "levels and scale ('town': {'lod': ..., 'lodScale': ...}): such rungs do not draw the town as measured\n", r);
                break;
            }
    std::unique_ptr<sim::Simulation> world;
    try {
        support::ProgressBar bar("building", 100, ranks.rank() == 0);
        // Ranks other than 0 draw nothing: they build what stepping their walkers needs, on rank 0's
        // navigation mesh (built once, not once per rank).
        sim::Simulation::BuildOptions options;
        // Posing their own walkers, they build every actor (the others' absent) but not the town's scene graph.
        if (distributed && ranks.rank() != 0)
            options = {o.poseOnRanks ? sim::Simulation::Scope::Actors : sim::Simulation::Scope::Walkers, receiveNavMesh(ranks)};
        world = sim::Simulation::build(scene, [&](const std::string& stage, double f) {
            support::StopSignals::throwIfStopped();
            bar.phase(std::size_t(f * 100), stage);
        }, options);
        if (distributed && ranks.size() > 1 && ranks.rank() == 0)
            ranks.broadcast(world->navMesh() ? world->navMesh()->toBytes() : sim::Bytes{}, town::kNavMeshTag, "navigation mesh");
        bar.finish(std::to_string(world->crowd().size()) + " actors");
        if (recorder) recorder->writeScene(world->root());
    } catch (const std::bad_alloc&) {  // the estimate was wrong for this scene or another process took the memory
        std::fprintf(stderr, "\nthrong-town%s: out of memory while building the world (%s); nothing written\n", rankLabel(ranks).c_str(),
                     (std::to_string(town::estimatedPeakBytes(scene) >> 20) + " MiB estimated, " +
                      std::to_string(town::availableMemory().bytes >> 20) + " MiB available now").c_str());
        if (ranks.size() > 1) ranks.abort(2);
        return 2;
    } catch (const support::StopRequested& e) {
        std::fprintf(stderr, "\nthrong-town%s: %s while building; nothing written\n", rankLabel(ranks).c_str(), e.what());
        if (ranks.size() > 1) ranks.abort(support::StopSignals::exitCode(e.signal()));
        return support::StopSignals::exitCode(e.signal());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "\nthrong-town%s: %s\n", rankLabel(ranks).c_str(), e.what());
        if (ranks.size() > 1) ranks.abort(2);
        return 2;
    }
    if (distributed) world->distribute(ranks, o.poseOnRanks);
    if (ranks.rank() != 0) return o.poseOnRanks ? town::poseShare(*world, ranks, o) : stepShare(*world, ranks, o);

    std::unique_ptr<town::TownRun> run;
    try {
        run = std::make_unique<town::TownRun>(o, *world, ranks, std::move(budget), std::move(recorder));
        if (run->windowed()) run->runWindowed();
        else run->runHeadless();
        run->finish();
    } catch (const ContextUnavailable& e) {  // the --gl kind asked for cannot be made: as a bad option
        std::fprintf(stderr, "throng-town: --gl %s: %s\n", o.gl.c_str(), e.what());
        if (ranks.size() > 1) ranks.abort(2);
        return 2;
    } catch (const support::StopRequested& e) {  // while baking impostors, before any frame
        std::fprintf(stderr, "\nthrong-town: %s while baking impostors; nothing written\n", e.what());
        if (ranks.size() > 1) ranks.abort(support::StopSignals::exitCode(e.signal()));
        return support::StopSignals::exitCode(e.signal());
    } catch (const std::exception& e) {  // a rank failed, stepping did (a region full), or the GL or a file could not be made
        std::fprintf(stderr, "\nthrong-town%s: %s\n", rankLabel(ranks).c_str(), e.what());
        // The frames drawn are kept: stats.csv ends at the last whole one, summary.json says why it stopped.
        if (run) try {
            run->finish(e.what());
        } catch (const std::exception& again) {
            std::fprintf(stderr, "throng-town: %s\n", again.what());
        }
        if (ranks.size() > 1) ranks.abort(3);
        return 3;
    }
    if (const int signal = run->stoppedBy()) {
        if (ranks.size() > 1) ranks.abort(support::StopSignals::exitCode(signal));  // the other ranks wait for frames that will not come
        return support::StopSignals::exitCode(signal);
    }
    return 0;
}
