// stats.csv and summary.json of a throng-town run (TownRecords.h).
#include "TownRecords.h"

#include <algorithm>
#include <sstream>

#include "throng/sim/PeakMemory.h"

namespace throng::town {
namespace {

// Columns ending in _ms are wall-clock times; the others depend only on the scene, seed and options.
const char* kCsvHeader =
    "frame,time,step_ms,app_ms,refpoint_ms,matrices_bounds_ms,cull_ms,skeleton_root_ms,cull2_ms,pose_ms,cull3_ms,draw_list_ms,"
    "draw_ms,scene_ms,mesh_ms,impostor_ms,morph_ms,impostor_draw_ms,frame_ms,actors_in_scene,culled_with_group,a,b,c1,c2,c3_1,c3_2,"
    "skeleton_nodes,eye_distances,draw_items,skinned_items,impostors,cells_morphed,primitives,draw_calls,triangles_drawn,"
    "occlusion_buffer_ms,refpoint_occlusion_ms,occluders_drawn,occluded_group,occluded_refpoint,occluded_sklsroot,"
    "occlusion_cells_hidden,occlusion_tests,occlusion_objects_tested,nodes_occluded,occlusion_rested,key_pose_band,key_pose_actors,key_pose_misses,key_pose_updates,"
    "key_pose_select_ms,key_pose_fills,background_morph_ms,ghosts,handovers,far_deferred,"
    "draw_cpu_ms,draw_gpu_ms,gpu_town_ms,gpu_meshes_ms,gpu_impostors_ms,gpu_finish_ms,gpu_frames_behind,"
    "face_evaluations,blink_evaluations,phrase_evaluations,face_ms,morph_instances,morph_targets_read,captions";

// With --frame-budget, the allocator's choice and its measure follow (app_cull_draw_ms is what it
// keeps under budget_ms).
const char* kBudgetCsvHeader = ",budget_ms,app_cull_draw_ms,over_budget,budget_rung,lod_scale,impostor_distance,key_pose_distance,morph_budget,render_scale,town_lod_scale";

}  // namespace

// Distributed, each rank's share of the step follows (rank0_agents, ..., rank1_agents, ...).
std::string csvHeader(int ranks, bool budget, bool posing) {
    std::string header = kCsvHeader;
    if (budget) header += kBudgetCsvHeader;
    for (int r = 0; r < ranks; ++r)
        for (const char* column : {"agents", "ghosts", "handovers", "handed_to_ranks", "border_bytes", "sent", "state_bytes", "work_ms", "wait_ms", "peak_bytes"})
            header += ",rank" + std::to_string(r) + "_" + column;
    // Posing on the ranks: what each posed, the bytes it sent for it, its APP+CULL and of that its
    // wait in the key-pose caches' exchanges.
    for (int r = 0; posing && r < ranks; ++r)
        for (const char* column : {"posed_items", "posing_bytes", "app_cull_ms", "pose_wait_ms"}) header += ",rank" + std::to_string(r) + "_" + column;
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
      << s.occlusionTests << ',' << s.occlusionObjectsTested << ',' << s.nodesOccluded << ',' << (s.occlusionRested ? 1 : 0) << ',' << s.keyPoseBand << ',' << s.keyPoseActors << ',' << s.keyPoseMisses
      << ',' << s.keyPoseUpdates << ',' << s.keyPoseSelectMs << ',' << r.meshes.keyPoseFills << ',' << r.quads.backgroundMorphMs << ','
      << f.ghosts << ',' << f.handovers << ',' << f.deferred << ',' << drawMs - r.presentMs;
    // GPU times: of this frame when the GPU has finished it (headless, always), else of the newest
    // frame it has (gpu_frames_behind); "nan" before any.
    if (r.gpu.frame < 0) o << ",nan,nan,nan,nan,nan,-1";
    else o << ',' << r.gpu.totalMs() << ',' << r.gpu.ms[0] << ',' << r.gpu.ms[1] << ',' << r.gpu.ms[2] << ',' << r.gpu.ms[3] << ',' << r.gpuFramesBehind;
    o << ',' << f.faceEvaluations[0] << ',' << f.faceEvaluations[1] << ',' << f.faceEvaluations[2] << ',' << f.faceMs << ','
      << r.meshes.morphInstances << ',' << r.meshes.morphTargetsRead << ',' << f.captions.size();
    if (budget) {
        const double cost = s.appCullMs() + drawMs;
        const sim::BudgetSettings& b = budget->ladder()[std::size_t(f.rung)].settings;
        o << ',' << budget->options().budgetMs << ',' << cost << ',' << (cost > budget->options().budgetMs ? 1 : 0) << ',' << f.rung << ','
          << b.lodScale << ',' << b.impostorDistance << ',' << b.keyPoseDistance << ',' << b.morphBudget << ',' << b.renderScale << ','
          << b.townLodScale;
    }
    for (const auto& share : f.ranks)
        o << ',' << share.agents << ',' << share.ghosts << ',' << share.handovers << ',' << share.handedToRanks << ','
          << share.borderBytes << ',' << share.sent << ',' << share.stateBytes << ',' << share.workMs << ',' << share.waitMs << ','
          << share.peakBytes;
    for (const auto& posed : f.posed) o << ',' << posed.items << ',' << posed.bytesSent << ',' << posed.appCullMs << ',' << posed.waitMs;
    return o.str() + '\n';
}

void Sums::add(const PreparedFrame& f, double drawMs, const CrowdRenderStatistics& drawn) {
    drawCpu += drawMs - drawn.presentMs;
    if (drawn.gpu.frame >= 0) drawGpu += drawn.gpu.totalMs(), ++gpuFrames;
    ranks.resize(std::max(ranks.size(), f.ranks.size()));
    for (std::size_t r = 0; r < f.ranks.size(); ++r) {
        sim::Locomotion::RankStepRecord& into = ranks[r];
        const sim::Locomotion::RankStepRecord& from = f.ranks[r];
        into.agents += from.agents, into.ghosts += from.ghosts, into.handovers += from.handovers;
        into.handedToRanks += from.handedToRanks, into.borderBytes += from.borderBytes, into.stateBytes += from.stateBytes;
        into.sent += from.sent;
        into.workMs += from.workMs, into.waitMs += from.waitMs;
        into.peakBytes = std::max(into.peakBytes, from.peakBytes);  // a peak, not a sum
    }
    posedShares.resize(std::max(posedShares.size(), f.posed.size()));
    for (std::size_t r = 0; r < f.posed.size(); ++r) {
        PreparedFrame::PosedShare& into = posedShares[r];
        into.items += f.posed[r].items, into.bytesSent += f.posed[r].bytesSent, into.appCullMs += f.posed[r].appCullMs;
        into.waitMs += f.posed[r].waitMs;
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
    faceEvaluations += double(f.faceEvaluations[0] + f.faceEvaluations[1] + f.faceEvaluations[2]);
    faceMs += f.faceMs;
    morphTargetsRead += double(drawn.meshes.morphTargetsRead);
    captions += double(f.captions.size());
    ++frames;
}

nlohmann::json summaryJson(const TownOptions& o, const sim::Simulation& world, const Sums& sums, double wallSeconds,
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
        j["shownMargin"] = world.shownMargin();    // of those, metres beyond the view walkers may be seen within
    }
    const double n = double(std::max<std::int64_t>(sums.frames, 1));
    j["peakMemoryBytes"] = sim::peakResidentBytes();  // this process's (rank 0's); each rank's in meanPerRank
    j["wallSeconds"] = wallSeconds;
    j["fps"] = sums.frames > 1 ? double(sums.frames - 1) / std::max(1e-9, wallSeconds - firstFrameSeconds) : 0.0;
    const char* names[9] = {"app", "refpoint", "matricesBounds", "cull", "skeletonRoot", "cull2", "pose", "cull3", "drawList"};
    for (int i = 0; i < 9; ++i) j["meanMs"][names[i]] = sums.phases[i] / n;
    j["meanMs"]["appCull"] = sums.app / n;
    j["meanMs"]["draw"] = sums.draw / n;
    j["meanMs"]["drawCpu"] = sums.drawCpu / n;  // DRAW less its wait for the GPU to finish the frame
    j["meanMs"]["drawGpu"] = sums.gpuFrames > 0 ? sums.drawGpu / double(sums.gpuFrames) : 0.0;  // timer queries
    j["meanMs"]["step"] = sums.step / n;  // the simulation step, before APP+CULL
    for (const auto& r : sums.ranks)  // distributed: each rank's share of a step, on average
        j["meanPerRank"].push_back({{"agents", double(r.agents) / n}, {"ghosts", double(r.ghosts) / n}, {"handovers", double(r.handovers) / n},
                                    {"handedToRanks", double(r.handedToRanks) / n}, {"borderBytes", double(r.borderBytes) / n},
                                    {"sent", double(r.sent) / n}, {"stateBytes", double(r.stateBytes) / n}, {"workMs", r.workMs / n}, {"waitMs", r.waitMs / n},
                                    {"peakBytes", r.peakBytes}});  // the largest resident memory any step reported
    for (std::size_t r = 0; r < sums.posedShares.size() && r < j["meanPerRank"].size(); ++r) {  // --pose-on-ranks: each rank's posing
        const PreparedFrame::PosedShare& p = sums.posedShares[r];
        j["meanPerRank"][r].update({{"posedItems", double(p.items) / n}, {"posingBytes", double(p.bytesSent) / n}, {"appCullMs", p.appCullMs / n},
                                    {"poseWaitMs", p.waitMs / n}});
    }
    j["mean"] = {{"posed", sums.posed / n}, {"skeletonNodes", sums.nodes / n}, {"drawItems", sums.items / n}, {"primitives", sums.primitives / n}, {"impostors", sums.impostors / n}};
    // Every effect Throng knows, zero when the scene did not declare it.
    j["faces"] = {{"evaluations", sums.faceEvaluations / n}, {"ms", sums.faceMs / n}, {"morphTargetsRead", sums.morphTargetsRead / n},
                  {"captions", sums.captions / n}};  // per frame: what the declared faces cost
    for (const char* effect : {"locomotion", "avoidance", "gaze", "idle", "flight", "occluders", "key-pose cache", "face", "blink", "phrase"}) {
        const auto c = world.effects().of(effect);
        j["effects"][effect] = {{"constructed", c.constructed}, {"ticks", c.ticks}};
    }
    return j;
}

}  // namespace throng::town
