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
// Under mpirun -np N every rank builds the same world and steps its share of the walkers' regions;
// rank 0 gathers the walkers near the frame's view after each step (the others cannot be seen),
// then culls, draws and writes as one process would (stats.csv adds each rank's share of the step).
// The files are the same with any number of ranks.
//
// With --frame-budget MS, a FrameBudgetAllocator picks each frame's rung of a ladder (LOD scale,
// impostor distance, key-pose distance, morph budget) from the APP+CULL+DRAW measured so far: a
// frame's cost is its APP+CULL (the processor's phases) plus its DRAW (beginFrame to endFrame), each
// timed on the thread that runs it; with --pipeline on they overlap the neighbouring frames' work
// (and share the cores with it), so a frame's cost is not the wall time between frames. The rung
// chosen after frame N's DRAW applies from the next frame prepared (N+2 pipelined, N+1 otherwise);
// a frame is processed and drawn with one rung, which stats.csv records.

#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "TownOptions.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/render/GlfwWindowContext.h"
#include "throng/render/ImageIO.h"
#include "throng/render/ImpostorSet.h"
#include "throng/scenegraph/FramePipeline.h"
#include "throng/scenegraph/OcclusionCulling.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/Ranks.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneError.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/sim/BudgetLadder.h"
#include "throng/sim/FrameBudgetAllocator.h"
#include "throng/support/ProgressBar.h"
#include "throng/support/SceneImpostors.h"
#include "throng/vtk/CrowdRecorder.h"

using namespace throng;
namespace fs = std::filesystem;

namespace {

// One frame between its APP/CULL and its DRAW: what DRAW and the statistics need of it.
struct PreparedFrame {
    std::int64_t number = 0;           // frame number
    double time = 0.0;                 // simulation time
    double stepMs = 0.0;               // the simulation step
    std::uint64_t ghosts = 0;          // walkers seen across a region border in that step
    std::uint64_t handovers = 0;       // walkers handed to another region at its end
    std::uint64_t deferred = 0;        // walkers of far regions that did not step (a declared approximation)
    Camera camera;                     // the camera it was culled for
    ActorFrameStatistics stats;        // APP and CULL
    const DrawList* list = nullptr;    // its draw list (the processor keeps it through the next frame)
    Image occlusion;                   // its occlusion buffer as a picture, when the window shows it
    std::vector<sim::Locomotion::RankStepRecord> ranks;  // each rank's share of the step, when distributed
    int rung = -1;                     // --frame-budget: the ladder rung it was processed and drawn with
};

// The occlusion buffer as a picture: near occluders light, far ones dark, nothing drawn clear. When
// the stage rests, the buffer is the last one built, from another view, and nothing is tested
// against it: it is shown grey and faint, so it is not read as this frame's.
Image occlusionPicture(const OcclusionBuffer& buffer, bool resting) {
    Image image;
    image.name = "occlusion buffer";
    image.width = buffer.width();
    image.height = buffer.height();
    image.rgba.resize(std::size_t(image.width) * std::size_t(image.height) * 4);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double d = buffer.depthAt(x, image.height - 1 - y);  // buffer row 0 is the bottom
            std::uint8_t* p = &image.rgba[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 4];
            const auto level = static_cast<std::uint8_t>(std::isfinite(d) ? 255.0 / (1.0 + d / 20.0) : 0.0);
            if (resting)
                p[0] = p[1] = p[2] = std::uint8_t(level / 2), p[3] = std::isfinite(d) ? 120 : 60;
            else
                p[0] = p[1] = level, p[2] = std::isfinite(d) ? 255 : 96, p[3] = std::isfinite(d) ? 230 : 140;
        }
    return image;
}

// Columns ending in _ms are wall-clock times; the others depend only on the scene, seed and options.
const char* kCsvHeader =
    "frame,time,step_ms,app_ms,refpoint_ms,matrices_bounds_ms,cull_ms,skeleton_root_ms,cull2_ms,pose_ms,cull3_ms,draw_list_ms,"
    "draw_ms,scene_ms,mesh_ms,impostor_ms,morph_ms,impostor_draw_ms,frame_ms,actors_in_scene,culled_with_group,a,b,c1,c2,c3_1,c3_2,"
    "skeleton_nodes,eye_distances,draw_items,skinned_items,impostors,cells_morphed,primitives,draw_calls,triangles_drawn,"
    "occlusion_buffer_ms,refpoint_occlusion_ms,occluders_drawn,occluded_group,occluded_refpoint,occluded_sklsroot,"
    "occlusion_cells_hidden,occlusion_tests,nodes_occluded,occlusion_rested,key_pose_band,key_pose_actors,key_pose_misses,key_pose_updates,"
    "key_pose_select_ms,key_pose_fills,background_morph_ms,ghosts,handovers,far_deferred";

// With --frame-budget, the allocator's choice and its measure follow (app_cull_draw_ms is what it
// keeps under budget_ms).
const char* kBudgetCsvHeader = ",budget_ms,app_cull_draw_ms,over_budget,budget_rung,lod_scale,impostor_distance,key_pose_distance,morph_budget,render_scale,town_lod_scale";

// Distributed, each rank's share of the step follows (rank0_agents, ..., rank1_agents, ...).
std::string csvHeader(int ranks, bool budget) {
    std::string header = kCsvHeader;
    if (budget) header += kBudgetCsvHeader;
    for (int r = 0; r < ranks; ++r)
        for (const char* column : {"agents", "ghosts", "handovers", "handed_to_ranks", "border_bytes", "sent", "state_bytes", "work_ms", "wait_ms"})
            header += ",rank" + std::to_string(r) + "_" + column;
    return header + "\n";
}

std::string csvRow(const PreparedFrame& f, double drawMs, double frameMs, const CrowdRenderStatistics& r,
                   const sim::FrameBudgetAllocator* budget) {
    const ActorFrameStatistics& s = f.stats;
    std::ostringstream o;
    o.precision(6);
    o << f.number << ',' << f.time << ',' << f.stepMs << ',' << s.appMs << ',' << s.refpointMs << ',' << s.matricesBoundsMs << ','
      << s.cullMs << ',' << s.skeletonRootMs << ',' << s.cull2Ms << ',' << s.poseMs << ',' << s.cull3Ms << ',' << s.drawListMs << ','
      << drawMs << ',' << r.sceneMs << ',' << r.meshMs << ',' << r.impostorBatchMs << ',' << r.morphMs << ','
      << r.impostorDrawMs << ',' << frameMs << ','
      << s.actorsInScene << ',' << s.culledWithGroup << ',' << s.a << ',' << s.b << ',' << s.c1 << ',' << s.c2 << ',' << s.c3_1
      << ',' << s.c3_2 << ',' << s.skeletonNodesEvaluated << ',' << s.eyeDistances << ',' << s.drawItems << ',' << r.skinnedItems
      << ',' << s.impostors << ',' << r.cellsMorphed << ',' << s.primitives << ',' << r.meshes.drawCalls + r.quads.drawCalls
      << ',' << r.meshes.triangles << ',' << s.occlusionBufferMs << ',' << s.refpointOcclusionMs << ',' << s.occludersDrawn << ','
      << s.occludedWithGroup << ',' << s.occludedRefpoint << ',' << s.occludedSklsroot << ',' << s.occlusionCellsHidden << ','
      << s.occlusionTests << ',' << s.nodesOccluded << ',' << (s.occlusionRested ? 1 : 0) << ',' << s.keyPoseBand << ',' << s.keyPoseActors << ',' << s.keyPoseMisses
      << ',' << s.keyPoseUpdates << ',' << s.keyPoseSelectMs << ',' << r.meshes.keyPoseFills << ',' << r.quads.backgroundMorphMs << ','
      << f.ghosts << ',' << f.handovers << ',' << f.deferred;
    if (budget) {
        const double cost = s.appCullMs() + drawMs;
        const sim::BudgetSettings& b = budget->ladder()[std::size_t(f.rung)].settings;
        o << ',' << budget->options().budgetMs << ',' << cost << ',' << (cost > budget->options().budgetMs ? 1 : 0) << ',' << f.rung << ','
          << b.lodScale << ',' << b.impostorDistance << ',' << b.keyPoseDistance << ',' << b.morphBudget << ',' << b.renderScale << ','
          << b.townLodScale;
    }
    for (const auto& share : f.ranks)
        o << ',' << share.agents << ',' << share.ghosts << ',' << share.handovers << ',' << share.handedToRanks << ','
          << share.borderBytes << ',' << share.sent << ',' << share.stateBytes << ',' << share.workMs << ',' << share.waitMs;
    return o.str() + '\n';
}

// Running sums of what summary.json reports as means.
struct Sums {
    double app = 0, phases[9] = {}, draw = 0, step = 0;
    double posed = 0, nodes = 0, items = 0, primitives = 0, impostors = 0;
    std::vector<sim::Locomotion::RankStepRecord> ranks;  // distributed: each rank's share, summed
    std::int64_t frames = 0;
    void add(const PreparedFrame& f, double drawMs) {
        ranks.resize(std::max(ranks.size(), f.ranks.size()));
        for (std::size_t r = 0; r < f.ranks.size(); ++r) {
            sim::Locomotion::RankStepRecord& into = ranks[r];
            const sim::Locomotion::RankStepRecord& from = f.ranks[r];
            into.agents += from.agents, into.ghosts += from.ghosts, into.handovers += from.handovers;
            into.handedToRanks += from.handedToRanks, into.borderBytes += from.borderBytes, into.stateBytes += from.stateBytes;
            into.sent += from.sent;
            into.workMs += from.workMs, into.waitMs += from.waitMs;
        }
        const ActorFrameStatistics& s = f.stats;
        app += s.appCullMs();
        const double p[9] = {s.appMs, s.refpointMs, s.matricesBoundsMs, s.cullMs, s.skeletonRootMs, s.cull2Ms, s.poseMs, s.cull3Ms, s.drawListMs};
        for (int i = 0; i < 9; ++i) phases[i] += p[i];
        draw += drawMs;
        step += f.stepMs;
        posed += double(s.actorsPosed);
        nodes += double(s.skeletonNodesEvaluated);
        items += double(s.drawItems);
        primitives += double(s.primitives);
        impostors += double(s.impostors);
        ++frames;
    }
};

std::string statusText(const sim::Simulation& world, const ActorFrameStatistics& s, double fps, double lodScale,
                       bool paused, bool shrunk, bool freeCamera, bool pipelined) {
    char buf[1024];
    std::snprintf(buf, sizeof buf,
                  "%s   %.1f fps   %s processing%s%s\n"
                  "actors %llu: culled with group %llu  A %llu  B %llu  C1 %llu  C2 %llu  C3.1 %llu  C3.2 %llu\n"
                  "posed %llu, skeleton nodes %llu, draw items %llu, triangles %llu\n"
                  "APP+CULL %.2f ms (APP %.2f, refpoints %.2f, bounds %.2f, CULL1 %.2f, roots %.2f, CULL2 %.2f, poses %.2f, CULL3 %.2f, list %.2f)\n"
                  "occlusion%s: %llu occluders drawn in %.2f ms; hidden: %llu with their group, %llu Refpoint, %llu Sklsroot, %llu tiles (O: buffer)\n"
                  "key-pose caches: %llu actors in the band, %llu drawn from a cache, %llu skinned (pose did not fit), %llu poses stored\n"
                  "LOD scale %.2f (+/-)   culling pyramid %s (C)   camera %s (Tab)   %s",
                  world.description().name.c_str(), fps, s.processing == Processing::Actor ? "actor" : "traditional",
                  pipelined ? ", DRAW overlapped" : "", paused ? "   PAUSED" : "", (unsigned long long)s.actorsInScene, (unsigned long long)s.culledWithGroup,
                  (unsigned long long)s.a, (unsigned long long)s.b, (unsigned long long)s.c1, (unsigned long long)s.c2,
                  (unsigned long long)s.c3_1, (unsigned long long)s.c3_2, (unsigned long long)s.actorsPosed,
                  (unsigned long long)s.skeletonNodesEvaluated, (unsigned long long)s.drawItems, (unsigned long long)s.primitives,
                  s.appCullMs(), s.appMs, s.refpointMs, s.matricesBoundsMs, s.cullMs, s.skeletonRootMs, s.cull2Ms, s.poseMs,
                  s.cull3Ms, s.drawListMs, s.occlusionRested ? " (resting: the last test hid little; O shows the last buffer, grey)" : "", (unsigned long long)s.occludersDrawn, s.occlusionBufferMs,
                  (unsigned long long)s.occludedWithGroup, (unsigned long long)s.occludedRefpoint, (unsigned long long)s.occludedSklsroot,
                  (unsigned long long)s.nodesOccluded, (unsigned long long)s.keyPoseBand, (unsigned long long)s.keyPoseActors,
                  (unsigned long long)s.keyPoseMisses, (unsigned long long)s.keyPoseUpdates, lodScale, shrunk ? "shrunk" : "full", freeCamera ? "free" : "path",
                  "W/A/S/D/Q/E move, drag to look, Space pause, P processing, Esc quit");
    return buf;
}

nlohmann::json summaryJson(const town::TownOptions& o, const sim::Simulation& world, const Sums& sums, double wallSeconds,
                           double firstFrameSeconds, int ranks) {
    nlohmann::json j;
    j["scene"] = world.description().name;
    j["sceneFile"] = o.scene;
    j["seed"] = world.description().seed;
    j["processing"] = o.processing;
    j["threads"] = o.threads;
    j["ranks"] = ranks;
    j["pipeline"] = o.pipeline;
    j["width"] = o.width;
    j["height"] = o.height;
    j["renderScale"] = o.renderScale;  // with --frame-budget, each rung's own (frameBudget.rungs)
    j["frames"] = sums.frames;
    j["step"] = world.description().step;
    j["actors"] = world.crowd().size();
    for (const auto& g : world.groups()) j["groups"].push_back({{"name", g.name}, {"behaviour", g.behaviour}, {"actors", g.actors.size()}});
    if (const auto* t = world.town()) j["town"] = {{"tilesX", t->tilesX}, {"tilesZ", t->tilesZ}, {"tileSize", t->tileSize}, {"triangles", world.townTriangles()}};
    if (const auto* nav = world.navMesh()) j["navMeshPolygons"] = nav->polygonCount();
    if (const auto* walkers = world.locomotion()) {
        j["regions"] = walkers->regionCount();
        j["gatherMargin"] = world.gatherMargin();  // metres beyond the view walkers are gathered within (under mpirun)
    }
    const double n = double(std::max<std::int64_t>(sums.frames, 1));
    j["wallSeconds"] = wallSeconds;
    j["fps"] = sums.frames > 1 ? double(sums.frames - 1) / std::max(1e-9, wallSeconds - firstFrameSeconds) : 0.0;
    const char* names[9] = {"app", "refpoint", "matricesBounds", "cull", "skeletonRoot", "cull2", "pose", "cull3", "drawList"};
    for (int i = 0; i < 9; ++i) j["meanMs"][names[i]] = sums.phases[i] / n;
    j["meanMs"]["appCull"] = sums.app / n;
    j["meanMs"]["draw"] = sums.draw / n;
    j["meanMs"]["step"] = sums.step / n;  // the simulation step, before APP+CULL
    for (const auto& r : sums.ranks)  // distributed: each rank's share of a step, on average
        j["meanPerRank"].push_back({{"agents", double(r.agents) / n}, {"ghosts", double(r.ghosts) / n}, {"handovers", double(r.handovers) / n},
                                    {"handedToRanks", double(r.handedToRanks) / n}, {"borderBytes", double(r.borderBytes) / n},
                                    {"sent", double(r.sent) / n}, {"stateBytes", double(r.stateBytes) / n}, {"workMs", r.workMs / n}, {"waitMs", r.waitMs / n}});
    j["mean"] = {{"posed", sums.posed / n}, {"skeletonNodes", sums.nodes / n}, {"drawItems", sums.items / n}, {"primitives", sums.primitives / n}, {"impostors", sums.impostors / n}};
    // Every effect Throng knows, zero when the scene did not declare it.
    for (const char* effect : {"locomotion", "avoidance", "gaze", "idle", "flight", "occluders", "key-pose cache"}) {
        const auto c = world.effects().of(effect);
        j["effects"][effect] = {{"constructed", c.constructed}, {"ticks", c.ticks}};
    }
    return j;
}

// Message tag of the start signal rank 0 sends when it is ready to step.
constexpr int kStartTag = 1;

// " (rank N)" in messages of a run of several ranks.
std::string rankLabel(const sim::Ranks& ranks) { return ranks.size() > 1 ? " (rank " + std::to_string(ranks.rank()) + ")" : ""; }

// A rank other than 0: waits for rank 0's set-up, then steps its share of the regions as often as
// rank 0 steps (once per frame), writing nothing. A failure stops every rank.
int stepShare(sim::Simulation& world, sim::Ranks& ranks, const town::TownOptions& o) {
    try {
        world.setThreads(unsigned(o.threads));
        const auto timeout = ranks.timeout();
        ranks.setTimeout(std::max<std::chrono::milliseconds>(timeout, std::chrono::minutes(30)));  // baking impostors takes a while
        ranks.broadcast({}, kStartTag, "start");
        ranks.setTimeout(timeout);
        for (std::int64_t f = 0; f < o.frames; ++f) world.step();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-town%s: %s\n", rankLabel(ranks).c_str(), e.what());
        ranks.abort(3);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    town::TownOptions o;
    sim::SceneDescription scene;
    std::unique_ptr<throng::vtk::CrowdRecorder> recorder;  // --vtk: crowd data for ParaView
    try {
        o = town::parseTownOptions(argc, argv, THRONG_TOWN_DEFAULT_SCENE, THRONG_TOWN_DEFAULT_LADDER);
        scene = sim::parseSceneFile(o.scene);
        if (o.actors) sim::scaleActors(scene, *o.actors);  // refuses a crowd the town cannot hold
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
    // Started by mpirun, each rank steps its share of the walkers' regions (one rank alone too, so
    // that `mpirun -np 1` takes the distributed path); rank 0 draws and writes.
    sim::Ranks ranks(std::chrono::milliseconds(std::llround(o.rankTimeout * 1000.0)));
    const bool distributed = sim::Ranks::launchedByMpi();
    // Only rank 0 writes, --vtk files too.
    if (!o.vtk.empty() && ranks.rank() == 0) try {
        recorder = std::make_unique<throng::vtk::CrowdRecorder>(o.vtk, o.vtkEvery);
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
    const double lodScale = o.lodScale > 0.0 ? o.lodScale : scene.representation.lodScale;

    std::unique_ptr<sim::Simulation> world;
    try {
        support::ProgressBar bar("building", 100, ranks.rank() == 0);
        world = sim::Simulation::build(scene, [&](const std::string& stage, double f) { bar.update(std::size_t(f * 100), stage); });
        bar.finish(std::to_string(world->crowd().size()) + " actors");
        if (recorder) recorder->writeScene(world->root());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "\nthrong-town%s: %s\n", rankLabel(ranks).c_str(), e.what());
        if (ranks.size() > 1) ranks.abort(2);
        return 2;
    }
    if (distributed) world->distribute(ranks);
    if (ranks.rank() != 0) return stepShare(*world, ranks, o);

    std::string why;
    const bool wantWindow = !o.headless && displayAvailable() && ranks.size() == 1;
    if (!o.headless && ranks.size() > 1) std::fprintf(stderr, "throng-town: %d ranks run headless\n", ranks.size());
    auto context = createContext({.width = o.width, .height = o.height, .window = wantWindow, .title = "Throng town"}, &why);
    const bool window = !context->headless();
    if (wantWindow && !window) std::fprintf(stderr, "throng-town: no window (%s): running headless\n", why.c_str());
    world->setThreads(unsigned(o.threads));
    ActorProcessor processor(world->crowd());
    processor.setProcessing(o.processing == "traditional" ? Processing::Traditional : Processing::Actor);
    processor.setThreads(unsigned(o.threads));
    processor.setLodScale(lodScale);
    const double townLodScale = world->townLodScale();  // the scene's; rungs may set their own
    // Occlusion culling when the scene declares it (and --occlusion does not turn it off).
    if (o.occlusion && world->description().representation.occlusion) processor.setOcclusion(world->description().representation.occlusion);
    // Key-pose caches for the middle band when the scene declares them (and --key-pose-cache does
    // not turn them off).
    if (o.keyPoseCache) world->attachKeyPoseCaches(processor);
    // Far actors as impostors when the scene asks for them (or --impostor-distance does, or a rung
    // of the --frame-budget ladder).
    double impostorDistance = o.impostorDistance >= 0.0 ? o.impostorDistance : world->description().representation.impostorDistance;
    if (budget) {
        impostorDistance = 0.0;
        for (const sim::BudgetRung& r : budget->ladder()) impostorDistance = std::max(impostorDistance, r.settings.impostorDistance);
    }
    std::unique_ptr<ImpostorSet> impostors;
    if (impostorDistance > 0.0) {
        impostors = support::bakeSceneImpostors(context, *world, true);
        impostors->attach(processor, impostorDistance, world->description().representation.hysteresis * impostorDistance);
    }
    CrowdRendererOptions rendererOptions;
    rendererOptions.impostors.morphBudget = budget ? budget->ladder()[std::size_t(budget->rung())].settings.morphBudget : o.morphBudget;
    rendererOptions.renderScale = float(budget ? budget->ladder()[std::size_t(budget->rung())].settings.renderScale : o.renderScale);
    rendererOptions.impostors.source = o.morph == "gl" ? MorphSource::Gpu : MorphSource::Cpu;
    rendererOptions.impostors.gridStep = o.morph == "grid" || o.morph == "background" ? 4 : 1;
    rendererOptions.impostors.backgroundMorph = o.morph == "background";
    rendererOptions.impostors.warp = o.cellWarp == "lines" ? CellWarp::FeatureLines : CellWarp::SurfaceProxy;
    CrowdRenderer renderer(context, rendererOptions);
    if (impostors) {  // the atlases on the GPU before the first frame, not during it
        std::vector<std::shared_ptr<const ImpostorDrawable>> drawables;
        for (std::size_t i = 0; i < impostors->size(); ++i) drawables.push_back(impostors->drawable(i));
        renderer.preloadImpostors(drawables);
    }
    const double aspect = double(o.width) / double(o.height);

    fs::create_directories(o.out);
    std::ofstream csv(fs::path(o.out) / "stats.csv");
    csv << csvHeader(distributed ? ranks.size() : 0, budget != nullptr);
    Sums sums;
    const auto start = std::chrono::steady_clock::now();
    double firstFrame = 0.0;
    auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };

    // The two stages of a frame. prepare: step the simulation (unless paused), then APP and CULL
    // for `camera`. draw: DRAW from the prepared frame's own data, then its statistics.
    PreparedFrame prepared[2];
    bool showOcclusion = false;  // the window's O key
    // --frame-budget: the rung of the next frame prepared (set between frames, on the main thread),
    // the rung the processor is set to, and the last frame drawn's rung and APP+CULL+DRAW.
    int nextRung = budget ? budget->rung() : -1, appliedRung = -1, drawnRung = -1;
    double drawnCost = 0.0;
    std::vector<std::int64_t> rungFrames(budget ? budget->ladder().size() : 0);
    std::int64_t framesWithin = 0;
    const bool caches = !processor.keyPoseCaches().empty();
    const double hysteresis = world->description().representation.hysteresis;
    auto applyRung = [&](int rung) {
        if (rung == appliedRung) return;
        const sim::BudgetSettings& b = budget->ladder()[std::size_t(rung)].settings;
        processor.setLodScale(b.lodScale);
        world->setTownLodScale(b.townLodScale > 0.0 ? b.townLodScale : townLodScale);
        if (impostors) processor.setImpostorDistance(b.impostorDistance, hysteresis * b.impostorDistance);
        if (caches) processor.setKeyPoseDistance(b.keyPoseDistance, hysteresis * b.keyPoseDistance);
        appliedRung = rung;
    };
    auto prepare = [&](PreparedFrame& f, std::int64_t number, const Camera& camera, bool step) {
        f.number = number;
        f.rung = nextRung;
        if (budget) applyRung(f.rung);
        f.stepMs = 0.0;
        f.ghosts = f.handovers = f.deferred = 0;
        f.ranks.assign(distributed ? std::size_t(ranks.size()) : 0, {});
        if (step) {
            // Distributed, the other ranks send only the walkers near this frame's view (a
            // recorder of every actor needs them all).
            if (distributed)
                world->setGatherView(recorder || o.gather == "all" ? std::nullopt : std::optional<Frustum>(camera.frustum()));
            world->step();
            f.stepMs = world->lastStepMs();
            if (const sim::Locomotion* walk = world->locomotion()) {
                f.ghosts = walk->lastGhostCount(), f.handovers = walk->lastHandoverCount(), f.deferred = walk->lastDeferredCount();
                if (!walk->rankSteps().empty()) f.ranks.assign(walk->rankSteps().begin(), walk->rankSteps().end());
            }
        }
        f.time = world->now().time;
        f.camera = camera;
        f.stats = processor.processFrame(world->root(), camera, f.time);
        f.list = &processor.drawList();
        if (recorder) try {
            recorder->record(world->crowd(), processor);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "\nthrong-town: --vtk: %s; recording stops\n", e.what());
            recorder.reset();  // finishes what was written
        }
        f.occlusion = showOcclusion && processor.occlusion() ? occlusionPicture(processor.occlusion()->buffer(), f.stats.occlusionRested) : Image{};
    };
    double lastFrameEnd = 0.0;
    auto draw = [&](const PreparedFrame& f, const std::function<void()>& beforePresent) {
        if (budget) {
            const sim::BudgetSettings& b = budget->ladder()[std::size_t(f.rung)].settings;
            renderer.setMorphBudget(b.morphBudget);
            renderer.setRenderScale(float(b.renderScale));
        }
        Stopwatch watch;
        renderer.beginFrame(f.camera);
        renderer.setOverlayImage(f.occlusion);
        renderer.draw(*f.list);
        if (beforePresent) beforePresent();
        renderer.endFrame();
        const double drawMs = watch.elapsedMs();
        const double now = seconds();
        sums.add(f, drawMs);
        csv << csvRow(f, drawMs, 1000.0 * (now - lastFrameEnd), renderer.statistics(), budget.get());
        if (budget) {
            drawnRung = f.rung;
            drawnCost = f.stats.appCullMs() + drawMs;
            ++rungFrames[std::size_t(f.rung)];
            if (drawnCost <= budget->options().budgetMs) ++framesWithin;
        }
        lastFrameEnd = now;
    };
    // After a frame's DRAW (both stages of the pipeline joined): the allocator learns its cost and
    // picks the rung of the next frame prepared.
    auto allocate = [&] {
        if (budget && drawnRung >= 0) nextRung = budget->observe(drawnRung, drawnCost);
    };
    FramePipeline pipeline(o.pipeline);
    // The other ranks wait for rank 0's set-up (impostors, GL) before the first step.
    if (ranks.size() > 1) ranks.broadcast({}, kStartTag, "start");

    try {
    if (!window) {
        support::ProgressBar bar("running", std::size_t(o.frames));
        if (o.every > 0) fs::create_directories(fs::path(o.out) / "frames");
        auto cameraAt = [&](double time) { return world->camera().at(time, aspect); };
        // Frame f's camera follows the path at frame f's time, known before it is stepped.
        const double step = world->description().step;
        prepare(prepared[0], 0, cameraAt(0.0), true);
        for (std::int64_t f = 0; f < o.frames; ++f) {
            PreparedFrame& current = prepared[f % 2];
            PreparedFrame& next = prepared[(f + 1) % 2];
            pipeline.run([&] { if (f + 1 < o.frames) prepare(next, f + 1, cameraAt(double(f + 1) * step), true); },
                         [&] {
                             draw(current, [&] {
                                 if (o.every > 0 && f % o.every == 0) {  // frame f: its own state, whatever the pipeline
                                     char name[64];
                                     std::snprintf(name, sizeof name, "frame_%06lld.png", (long long)f);
                                     writePng(renderer.readFrame(), (fs::path(o.out) / "frames" / name).string());
                                 }
                             });
                         });
            allocate();
            if (f == 0) firstFrame = seconds();
            char detail[128];
            std::snprintf(detail, sizeof detail, "frame %lld/%lld, %.1f fps", (long long)f + 1, (long long)o.frames,
                          f > 0 ? double(f) / std::max(1e-9, seconds() - firstFrame) : 0.0);
            bar.update(std::size_t(f + 1), detail);
        }
        bar.finish();
    } else {
        auto* glfw = static_cast<GlfwWindowContext*>(context.get())->window();
        bool paused = false, shrunk = false, freeCamera = false;
        double scale = lodScale, yaw = 0.0, pitch = -0.3, lastX = 0.0, lastY = 0.0;
        glm::dvec3 position(0.0, 30.0, 60.0);
        std::map<int, bool> held;
        auto pressed = [&](int key) {  // once per press
            const bool down = glfwGetKey(glfw, key) == GLFW_PRESS;
            const bool edge = down && !held[key];
            held[key] = down;
            return edge;
        };
        // The camera of the next frame, from the keyboard and mouse (main thread only).
        auto nextCamera = [&](double time) {
            Camera camera = world->camera().at(time, aspect);
            if (pressed(GLFW_KEY_TAB)) {
                freeCamera = !freeCamera;
                if (freeCamera) {  // start from where the path camera is
                    position = camera.eye();
                    const glm::dvec3 f = -glm::dvec3(glm::transpose(glm::dmat3(camera.view()))[2]);
                    yaw = std::atan2(f.x, -f.z);
                    pitch = std::asin(std::clamp(f.y, -1.0, 1.0));
                }
            }
            double x, y;
            glfwGetCursorPos(glfw, &x, &y);
            if (glfwGetMouseButton(glfw, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && freeCamera) {
                yaw += (x - lastX) * 0.004;
                pitch = std::clamp(pitch - (y - lastY) * 0.004, -1.5, 1.5);
            }
            lastX = x, lastY = y;
            if (freeCamera) {
                const glm::dvec3 forward(std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
                const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
                const double speed = glfwGetKey(glfw, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 3.0 : 0.6;
                if (glfwGetKey(glfw, GLFW_KEY_W) == GLFW_PRESS) position += forward * speed;
                if (glfwGetKey(glfw, GLFW_KEY_S) == GLFW_PRESS) position -= forward * speed;
                if (glfwGetKey(glfw, GLFW_KEY_D) == GLFW_PRESS) position += right * speed;
                if (glfwGetKey(glfw, GLFW_KEY_A) == GLFW_PRESS) position -= right * speed;
                if (glfwGetKey(glfw, GLFW_KEY_E) == GLFW_PRESS) position.y += speed;
                if (glfwGetKey(glfw, GLFW_KEY_Q) == GLFW_PRESS) position.y -= speed;
                camera.setLookAt(position, position + forward, glm::dvec3(0, 1, 0));
            }
            // The shrunken pyramid culls as if the view were 60% as wide: actors vanish near the edges.
            if (shrunk) {
                Camera narrow = camera;
                const auto& d = world->description().camera;
                narrow.setPerspective(0.6 * d.fovDegrees * std::numbers::pi / 180.0, aspect, d.nearDistance, d.farDistance);
                processor.setCullingFrustum(narrow.frustum());
            } else {
                processor.setCullingFrustum(std::nullopt);
            }
            return camera;
        };
        const double step = world->description().step;
        auto last = std::chrono::steady_clock::now();
        double fps = 0.0;
        prepare(prepared[0], 0, nextCamera(0.0), true);
        for (std::int64_t f = 0; !context->shouldClose() && !(o.framesGiven && f >= o.frames); ++f) {
            context->pollEvents();
            if (glfwGetKey(glfw, GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
            if (pressed(GLFW_KEY_SPACE)) paused = !paused;
            if (pressed(GLFW_KEY_C)) shrunk = !shrunk;
            if (pressed(GLFW_KEY_O)) showOcclusion = !showOcclusion;
            if (pressed(GLFW_KEY_P))
                processor.setProcessing(processor.processing() == Processing::Actor ? Processing::Traditional : Processing::Actor);
            if (pressed(GLFW_KEY_EQUAL) || pressed(GLFW_KEY_KP_ADD)) processor.setLodScale(scale *= 1.25);
            if (pressed(GLFW_KEY_MINUS) || pressed(GLFW_KEY_KP_SUBTRACT)) processor.setLodScale(scale /= 1.25);
            PreparedFrame& current = prepared[f % 2];
            PreparedFrame& next = prepared[(f + 1) % 2];
            const bool advance = !paused;
            const Camera camera = nextCamera(world->now().time + (advance ? step : 0.0));
            renderer.setOverlayText(statusText(*world, current.stats, fps, scale, paused, shrunk, freeCamera, o.pipeline));
            pipeline.run([&] { prepare(next, f + 1, camera, advance); }, [&] { draw(current, {}); });
            allocate();
            const auto now = std::chrono::steady_clock::now();
            const double dt = std::chrono::duration<double>(now - last).count();
            last = now;
            fps = fps == 0.0 ? 1.0 / std::max(dt, 1e-6) : 0.9 * fps + 0.1 / std::max(dt, 1e-6);
        }
    }
    } catch (const std::exception& e) {  // a rank failed, or stepping did (a region full)
        std::fprintf(stderr, "\nthrong-town%s: %s\n", rankLabel(ranks).c_str(), e.what());
        if (ranks.size() > 1) ranks.abort(3);
        return 3;
    }
    const double wall = seconds();
    if (recorder) try {
        recorder->finish();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-town: --vtk: %s\n", e.what());
    }
    nlohmann::json summary = summaryJson(o, *world, sums, wall, firstFrame, ranks.size());
    if (budget) {
        nlohmann::json& b = summary["frameBudget"];
        b["budgetMs"] = o.frameBudget;
        b["ladder"] = o.frameBudgetLadder;
        b["measure"] = "app_cull_draw_ms: APP+CULL plus DRAW of the same frame, each timed on its own thread";
        b["framesWithinBudget"] = framesWithin;
        b["shareWithinBudget"] = double(framesWithin) / double(std::max<std::int64_t>(sums.frames, 1));
        b["rungChanges"] = budget->changes();
        for (std::size_t r = 0; r < rungFrames.size(); ++r) {
            const sim::BudgetRung& rung = budget->ladder()[r];
            b["rungs"].push_back({{"rung", r}, {"settings", sim::budgetRungValue(rung.settings)}, {"frames", rungFrames[r]},
                                  {"ladderMs", rung.ms}, {"ladderPixelsOff8", rung.error}, {"measuredMs", budget->measuredMs(int(r))}});
        }
        std::fprintf(stderr, "throng-town: APP+CULL+DRAW within %.1f ms on %.1f %% of frames\n", o.frameBudget,
                     100.0 * double(framesWithin) / double(std::max<std::int64_t>(sums.frames, 1)));
    }
    std::ofstream(fs::path(o.out) / "summary.json") << summary.dump(2) << '\n';
    std::fprintf(stderr, "throng-town: %lld frames in %.1f s; stats.csv, summary.json%s in %s\n", (long long)sums.frames, wall,
                 !window && o.every > 0 ? " and frames/" : "", o.out.c_str());
    return 0;
}
