// OpenSceneGraph side by side: the same crowd processed by OSG 3.6 (UpdateVisitor + CullVisitor
// through osgUtil::SceneView), by Throng's traditional processing and by Throng's actor processing
// (APP+CULL, one thread), in the same process, for the same camera and time. The methods alternate
// within every frame (their order rotating), so machine noise touches all alike; the table gives
// the median of N frames in milliseconds and the ratios OSG / traditional and OSG / actor.
//
// Every frame, untimed, the program also checks that they agree on what is visible: the (actor,
// part, level) triples OSG put in its render bins against those in Throng's draw lists. OSG and
// traditional processing pose every actor at full precision; so does actor processing once its
// behavioural LOD is switched off, and that untimed run must agree with them too. The timed actor
// frame (Throng's defaults: far actors hold the previous key) may differ from them only where the
// untimed one does not, that is by its behavioural LOD alone: such differences are counted and
// shown. The program prints the check and exits with 1 if any other difference appears.

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <osg/Version>

#include "OsgCrowd.h"
#include "PeerScene.h"
#include "VisibleParts.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/OutputPaths.h"
#include "throng/scenegraph/Stopwatch.h"

using namespace throng;
using namespace throng::peers;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One row of the table: a scene at one size.
struct Row {
    std::string scene;
    std::size_t actors = 0;
    std::size_t frames = 0;
    std::size_t osgNodes = 0;
    double visibleActors = 0, visibleParts = 0;  // medians over the frames
    double osgUpdateMs = 0, osgCullMs = 0, osgMs = 0, traditionalMs = 0, actorMs = 0;
    std::size_t framesDiffering = 0;     // frames where OSG or full-precision actor processing differ from traditional
    std::size_t framesLodDiffering = 0;  // frames where the timed actor processing differs, by its behavioural LOD only
    std::size_t lodPartsMax = 0;    // the most parts that differed so in one frame
    std::size_t lodDroppedMax = 0;  // the most actors traditional processing drew and actor processing did not, in one frame
    std::size_t lodAddedMax = 0;    // the most actors actor processing drew and traditional processing did not, in one frame
};

// How two sets of visible parts differ.
struct Comparison {
    SetDifference<ActorId> actors;
    SetDifference<VisiblePart> parts;
    bool empty() const { return actors.empty() && parts.empty(); }
};

Comparison compare(const std::vector<VisiblePart>& a, const std::vector<VisiblePart>& b) {
    const std::vector<ActorId> actorsA = actorsOf(a), actorsB = actorsOf(b);
    return {difference<ActorId>(actorsA, actorsB), difference<VisiblePart>(a, b)};
}

// Prints how `a` and `b` (named) differ in frame `frame`, with the first few parts of each side.
void print(const char* a, const char* b, const Comparison& c, std::size_t frame, const char* note = "") {
    std::printf("  frame %zu: %s and %s differ%s: %zu actors only in %s, %zu only in %s; %zu parts only in %s, %zu only in %s\n",
                frame, a, b, note, c.actors.onlyInFirst.size(), a, c.actors.onlyInSecond.size(), b, c.parts.onlyInFirst.size(), a,
                c.parts.onlyInSecond.size(), b);
    auto show = [](const char* who, const std::vector<VisiblePart>& list) {
        for (std::size_t i = 0; i < std::min<std::size_t>(list.size(), 5); ++i)
            std::printf("    only in %s: actor %u part %u level %u\n", who, list[i].actor, list[i].part, list[i].level);
    };
    show(a, c.parts.onlyInFirst);
    show(b, c.parts.onlyInSecond);
}

// Runs one actor-processing frame with behavioural LOD on or off; returns its time and what it drew.
double actorFrame(ActorProcessor& processor, PeerScene& scene, double time, bool behaviouralLod, std::vector<VisiblePart>& parts) {
    processor.setProcessing(Processing::Actor);
    processor.setBehaviouralLod(behaviouralLod);
    Stopwatch watch;
    processor.processFrame(*scene.root, scene.camera, time);
    const double ms = watch.elapsedMs();
    parts = peers::visibleParts(processor.drawList());
    return ms;
}

Row run(const std::string& sceneName, std::size_t actors, std::size_t frames, const OsgCrowdOptions& osgOptions) {
    Stopwatch build;
    PeerScene scene = buildPeerScene(sceneName, actors);
    const double throngBuildS = build.elapsedMs() / 1000.0;
    ActorProcessor processor(*scene.crowd);  // one thread, Throng's defaults (skeletal and behavioural LOD)
    build.restart();
    auto osgCrowd = std::make_unique<OsgCrowd>(*scene.crowd, *scene.root, osgOptions);
    OsgCrowd& osg = *osgCrowd;
    osg.setCamera(scene.camera);
    Row row;
    row.scene = sceneName;
    row.actors = actors;
    row.frames = frames;
    row.osgNodes = osg.nodeCount();
    std::printf("%s, %zu actors: Throng scene built in %.1f s, OSG copy (%zu nodes) in %.1f s\n", sceneName.c_str(), actors,
                throngBuildS, row.osgNodes, build.elapsedMs() / 1000.0);
    std::fflush(stdout);

    std::vector<double> osgUpdate, osgCull, osgTotal, traditional, actor, visibleActors, visibleParts;
    // Frame 0 warms every method up (first-touch allocations) and is checked but not timed.
    for (std::size_t f = 0; f <= frames; ++f) {
        const double time = scene.timeOf(f);
        std::vector<VisiblePart> osgParts, traditionalParts, actorParts, exactParts;
        OsgFrameTimes o;
        double t = 0.0, a = 0.0;
        for (std::size_t k = 0; k < 3; ++k) {
            switch ((f + k) % 3) {  // the order rotates from frame to frame
                case 0:
                    o = osg.frame(time);
                    osgParts = osg.visibleParts();
                    break;
                case 1: {
                    processor.setProcessing(Processing::Traditional);
                    Stopwatch watch;
                    processor.processFrame(*scene.root, scene.camera, time);
                    t = watch.elapsedMs();
                    traditionalParts = peers::visibleParts(processor.drawList());
                    break;
                }
                default: a = actorFrame(processor, scene, time, true, actorParts);
            }
        }
        // Untimed: actor processing posing every actor at full precision, as traditional
        // processing and OSG do. Behavioural LOD (held keys beyond 60 m) is the one setting in
        // which the timed actor frame may legitimately differ from them.
        actorFrame(processor, scene, time, false, exactParts);
        processor.setBehaviouralLod(true);

        const Comparison osgVsTraditional = compare(osgParts, traditionalParts);
        const Comparison exactVsTraditional = compare(exactParts, traditionalParts);
        const Comparison actorVsTraditional = compare(actorParts, traditionalParts);
        const bool failed = !osgVsTraditional.empty() || !exactVsTraditional.empty();
        if (!osgVsTraditional.empty()) print("OSG", "traditional", osgVsTraditional, f);
        if (!exactVsTraditional.empty()) print("actor (behavioural LOD off)", "traditional", exactVsTraditional, f);
        if (!actorVsTraditional.empty()) {
            print("actor", "traditional", actorVsTraditional, f, failed ? "" : " (behavioural LOD only: with it off they agree)");
            if (!failed) {
                ++row.framesLodDiffering;
                row.lodPartsMax = std::max(row.lodPartsMax, actorVsTraditional.parts.onlyInFirst.size() + actorVsTraditional.parts.onlyInSecond.size());
                row.lodDroppedMax = std::max(row.lodDroppedMax, actorVsTraditional.actors.onlyInSecond.size());
                row.lodAddedMax = std::max(row.lodAddedMax, actorVsTraditional.actors.onlyInFirst.size());
            }
        }
        row.framesDiffering += failed;
        if (f == 0) continue;
        osgUpdate.push_back(o.updateMs);
        osgCull.push_back(o.cullMs);
        osgTotal.push_back(o.totalMs());
        traditional.push_back(t);
        actor.push_back(a);
        visibleActors.push_back(double(actorsOf(traditionalParts).size()));
        visibleParts.push_back(double(traditionalParts.size()));
    }
    Stopwatch teardown;
    osgCrowd.reset();
    std::printf("  OSG copy taken apart in %.1f s\n", teardown.elapsedMs() / 1000.0);
    row.osgUpdateMs = median(osgUpdate);
    row.osgCullMs = median(osgCull);
    row.osgMs = median(osgTotal);
    row.traditionalMs = median(traditional);
    row.actorMs = median(actor);
    row.visibleActors = median(visibleActors);
    row.visibleParts = median(visibleParts);
    if (row.framesDiffering) {
        std::printf("  visible-set check: DIFFERENT in %zu of %zu frames\n", row.framesDiffering, frames + 1);
    } else {
        std::printf("  visible-set check: OSG, traditional and actor processing identical in all %zu frames (median %.0f actors, %.0f parts visible)\n",
                    frames + 1, row.visibleActors, row.visibleParts);
        if (row.framesLodDiffering)
            std::printf("  (with its default behavioural LOD, actor processing differed in %zu frames, by at most %zu part(s); "
                        "whole actors it dropped / added: at most %zu / %zu)\n",
                        row.framesLodDiffering, row.lodPartsMax, row.lodDroppedMax, row.lodAddedMax);
    }
    std::fflush(stdout);
    return row;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"OpenSceneGraph 3.6 side by side with Throng's traditional and actor processing (APP+CULL, one thread)",
                 "bench_osg_peer"};
    std::vector<std::size_t> sizes{1000, 10000, 100000};
    std::vector<std::string> sceneNames{"table2", "town"};
    std::size_t frames = 15;
    std::string csvPath;
    app.add_option("--actors", sizes, "actor counts (comma separated)")->delimiter(',')->check(CLI::Range(std::size_t{1}, std::size_t{10000000}))->capture_default_str();
    app.add_option("--scenes", sceneNames,
                   "scenes: table2 (Table 2's proportions), town (town-like spread), town-dense (100 times as dense, near and far planes at 5 and 60 m: for the check)")
        ->delimiter(',')->check(CLI::IsMember({"table2", "town", "town-dense"}))->capture_default_str();
    app.add_option("--frames", frames, "timed frames per scene and size (the median is reported)")->check(CLI::Range(std::size_t{1}, std::size_t{100000}))->capture_default_str();
    app.add_option("--csv", csvPath, "also write the table to this CSV file")->type_name("FILE")
        ->check(CLI::Validator([](std::string& path) { return problemWritingFile(path); }, "FILE"));
    OsgCrowdOptions osgOptions;
    bool osgDefaults = false;
    app.add_flag("--osg-defaults", osgDefaults,
                 "run OSG with its default culling (sides only, near/far computed, small-feature culling), LOD centres "
                 "and leaf boxes: the visible sets then differ, and the check says where");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << app.get_name() << ": error: " << e.what() << "\n";
        return 2;
    }
    std::ofstream csv;
    if (!csvPath.empty()) {
        csv.open(csvPath);
        if (!csv) {
            std::cerr << "bench_osg_peer: error: --csv: cannot open '" << csvPath << "' for writing\n";
            return 2;
        }
    }

    osgOptions.matchThrong = !osgDefaults;
    std::printf("OpenSceneGraph %s (%s); APP+CULL on one thread; median of %zu frames per row\n", osgGetVersion(),
                osgDefaults ? "its default settings" : "set to cull and choose levels as Throng does", frames);
    std::vector<Row> rows;
    try {
        for (const std::string& name : sceneNames)
            for (std::size_t n : sizes) rows.push_back(run(name, n, frames, osgOptions));
    } catch (const std::exception& e) {
        std::cerr << "bench_osg_peer: error: " << e.what() << "\n";
        return 1;
    }

    std::printf("\n| scene | actors | visible actors | OSG update | OSG cull | OSG total | Throng traditional | Throng actor | OSG / traditional | OSG / actor | visible sets |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    bool same = true;
    for (const Row& r : rows) {
        same = same && r.framesDiffering == 0;
        std::string check = r.framesDiffering ? "differ" : "identical";
        if (!r.framesDiffering && r.framesLodDiffering)
            check += " (behavioural LOD: " + std::to_string(r.lodPartsMax) + " part(s), actors dropped / added " +
                     std::to_string(r.lodDroppedMax) + " / " + std::to_string(r.lodAddedMax) + ")";
        std::printf("| %s | %zu | %.0f | %.3f ms | %.3f ms | %.3f ms | %.3f ms | %.3f ms | %.2f | %.2f | %s |\n", r.scene.c_str(), r.actors,
                    r.visibleActors, r.osgUpdateMs, r.osgCullMs, r.osgMs, r.traditionalMs, r.actorMs, r.osgMs / r.traditionalMs,
                    r.osgMs / r.actorMs, check.c_str());
    }
    if (csv.is_open()) {
        csv << "scene,actors,frames,osg_nodes,visible_actors,visible_parts,osg_update_ms,osg_cull_ms,osg_ms,traditional_ms,actor_ms,"
               "osg_over_traditional,osg_over_actor,frames_differing,frames_behavioural_lod_differing,behavioural_lod_parts_max,"
               "behavioural_lod_actors_dropped_max,behavioural_lod_actors_added_max\n";
        for (const Row& r : rows)
            csv << r.scene << ',' << r.actors << ',' << r.frames << ',' << r.osgNodes << ',' << r.visibleActors << ','
                << r.visibleParts << ',' << r.osgUpdateMs << ',' << r.osgCullMs << ',' << r.osgMs << ',' << r.traditionalMs << ','
                << r.actorMs << ',' << r.osgMs / r.traditionalMs << ',' << r.osgMs / r.actorMs << ',' << r.framesDiffering << ','
                << r.framesLodDiffering << ',' << r.lodPartsMax << ',' << r.lodDroppedMax << ',' << r.lodAddedMax << '\n';
        if (!csv) {
            std::cerr << "bench_osg_peer: error: --csv: writing '" << csvPath << "' failed\n";
            return 1;
        }
    }
    std::printf("\nvisible sets: %s\n", same ? "OSG, traditional and actor processing agree in every frame" : "DIFFERENT (see above)");
    return same ? 0 : 1;
}
