// bench_keypose_timeline: seed 004's Figure 12, the frame-to-frame coherence of a key-pose cache.
// A fixed camera sees a crowd standing on a grid, every actor in the cache's band (beyond its
// distance, no impostors), one template with one cache of --rows key-poses (the paper: about 2,500
// agents in view, 100 key-poses per template). At t = 0 every actor picks one of the five clips at
// random with a random time offset; at 5 s the choice is cut to the first clip, and every 5 s one
// more becomes available, all five again at 25 s (ClipSchedule). Each frame, for the intermittent
// (the paper's A) and the interpolative (B) cache, it records the actors the cache serves and
// misses and the key-poses stored anew (updates). Time is simulated (frame n at n / --fps s) and
// the choices come from --seed, so a run is deterministic; nothing is rendered (what is measured is
// the cache's choice each frame, which ActorProcessor makes during CULL).
//
// Clips: the paper's five are clapping, jumping, cheering, shouting and idle (200 key-poses in all),
// cheering first. Ours are the robot's (../shared/assets/characters/robot.glb, CC0): Robot_ThumbsUp
// (cheering), Robot_Idle, Robot_Wave (clapping), Robot_Yes (shouting), Robot_Jump (jumping), in the
// order they become available (--clips). The robot's clips are RobotExpressive.glb's (same names
// without the prefix, same durations), but RobotExpressive draws parts of its body as rigid meshes
// on joints, which a key-pose cache cannot hold (KeyPoseCache refuses it); robot.glb is skinned
// throughout. The paper names only the first clip; we order the rest so that, as in its reading,
// one and then two clips fit a 100-row cache and a third does not (at 15 key-poses a second the
// first k clips need 24, 74, 102, 127 and 138 key-poses; its five needed 200).
//
// Who chooses again when the set changes: the paper says only that "the choice of animation is
// reduced" and that each new one is "made available for selection". At each 5-s boundary an actor
// whose clip is no longer offered must choose again; if no one else did, nobody would ever take
// up a clip added later (nothing is removed after 5 s), so every other actor chooses again too
// (--repick 1, the default): each phase then starts as t = 0 did, a uniform choice among the
// offered clips with random offsets, and within a phase nobody changes. --repick P lets each
// actor whose clip is still offered choose again with probability P instead (0: only those who
// must), for comparison.
//
// Writes into --out: keypose-timeline.csv (per frame and mode: time, clips available, actors in
// the band, served, misses, updates, key-poses wanted and held), keypose-timeline-phases.csv (per
// phase and mode: the means), keypose-timeline-clips.csv (each clip's duration and key-poses),
// and two charts through VTK, keypose-timeline-served.png and keypose-timeline-updates.png (VTK's
// charts have one vertical axis: the paper's two axes are two charts; without a display run under
// xvfb-run -a, else no chart is written and the run says so). Prints a Markdown summary: per phase
// and mode, the mean share served, the misses and the updates a frame.
//
//   bench_keypose_timeline [--out DIR] [--character FILE] [--clips A,B,...] [--actors 2500]
//                          [--rows 100] [--rate 15] [--fps 30] [--phase 5] [--repick 1]
//                          [--seed 1] [--threads 1]
// Exit codes: 0 done, 1 the run failed (the message says why), 2 a bad command line (a clip the
// character lacks included).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "KeyPoseTimeline.h"
#include "throng/actors/Actor.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/actors/AnimationClip.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/bench/Experiment.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/testkit/Assets.h"
#include "throng/vtk/Chart.h"

using namespace throng;

namespace {

// One cache mode's processor and what it recorded.
struct Run {
    const char* name;        // in the CSV and the table
    const char* label;       // in the charts
    KeyPoseMode mode;
    std::unique_ptr<ActorProcessor> processor;
    std::shared_ptr<KeyPoseCache> cache;
    std::vector<bench::TimelineFrame> frames;
};

std::string percent(double share) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", 100.0 * share);
    return text;
}

}  // namespace

int main(int argc, char** argv) {
    std::string outText = "keypose-timeline";
    std::string character = testkit::characterPath("robot.glb");
    std::vector<std::string> clipNames{"Robot_ThumbsUp", "Robot_Idle", "Robot_Wave", "Robot_Yes", "Robot_Jump"};
    std::uint32_t actors = 2500, rows = 100, fps = 30, seed = 1, threads = 1;
    double rate = 15.0, phaseSeconds = 5.0, repick = 1.0;
    // Not a frame-level experiment of the town: the harness gives it its command line only.
    bench::Experiment experiment("bench_keypose_timeline",
                                 "Seed 004 Figure 12: actors a key-pose cache serves and the key-poses it stores each frame while the\n"
                                 "clips a fixed crowd may choose from go from five to one and back to five, one more every phase, for\n"
                                 "the intermittent and the interpolative cache. Writes keypose-timeline.csv, -phases.csv, -clips.csv and\n"
                                 "two PNG charts (through VTK: without a display, run under xvfb-run -a); prints a Markdown summary.",
                                 0, {});
    CLI::App& app = experiment.app();
    app.add_option("--out", outText, "folder for the report")->type_name("DIR")->check(bench::folderToWrite());
    experiment.markOutput("--out");
    app.add_option("--character", character, "glTF character whose first skinned template the crowd uses")
        ->type_name("FILE")
        ->check(CLI::ExistingFile)
        ->default_str("../shared/assets/characters/robot.glb");
    app.add_option("--clips", clipNames, "the character's clips, in the order they become available (phase k offers the first k)")
        ->type_name("NAME,...")
        ->delimiter(',')
        ->expected(1, 64);
    app.add_option("--actors", actors, "actors, on a grid in front of the camera, all in the cache's band")
        ->type_name("N")
        ->check(CLI::Range(1u, 1000000u));
    app.add_option("--rows", rows, "key-poses the cache holds (the template's one cache, each mode)")->type_name("N")->check(CLI::Range(1u, 65535u));
    app.add_option("--rate", rate, "key-poses per second of clip")->type_name("R")->check(bench::finiteNumber(0.1, 1000.0));
    app.add_option("--fps", fps, "frames per simulated second")->type_name("N")->check(CLI::Range(1u, 1000u));
    app.add_option("--phase", phaseSeconds, "seconds each phase lasts (the run lasts (clips + 1) phases)")
        ->type_name("S")
        ->check(bench::finiteNumber(0.01, 3600.0));
    app.add_option("--repick", repick, "probability that an actor whose clip is still offered chooses again at a phase boundary")
        ->type_name("P")
        ->check(bench::finiteNumber(0.0, 1.0));
    app.add_option("--seed", seed, "seed of the actors' choices")->type_name("N")->check(CLI::Range(0u, 4000000000u));
    app.add_option("--threads", threads, "threads of each processor's per-actor work (results do not depend on it)")
        ->type_name("N")
        ->check(CLI::Range(1u, 256u));
    if (const auto code = experiment.parse(argc, argv)) return *code;

    // Clip names: checked against each other before anything is loaded.
    {
        std::set<std::string> seen;
        for (const std::string& name : clipNames) {
            if (name.empty()) {
                std::fprintf(stderr, "bench_keypose_timeline: --clips: an empty clip name\n");
                return bench::Experiment::kUsageError;
            }
            if (!seen.insert(name).second) {
                std::fprintf(stderr, "bench_keypose_timeline: --clips: '%s' is listed twice\n", name.c_str());
                return bench::Experiment::kUsageError;
            }
        }
    }
    try {
        const std::filesystem::path out = outText;
        const CharacterAsset asset = loadCharacter(character);
        const std::shared_ptr<const ActorTemplate> tmpl = asset.primaryTemplate();
        if (!tmpl) throw std::runtime_error(character + ": no template");
        std::vector<int> clips;
        for (const std::string& name : clipNames) {
            const int c = tmpl->findClip(name);
            if (c < 0) {
                std::string names;
                for (const auto& clip : tmpl->clips()) names += (names.empty() ? "" : ", ") + clip->name();
                std::fprintf(stderr, "bench_keypose_timeline: --clips: %s has no clip '%s' (its clips: %s)\n", character.c_str(), name.c_str(),
                             names.c_str());
                return bench::Experiment::kUsageError;
            }
            clips.push_back(c);
        }
        const bench::ClipSchedule schedule{static_cast<std::uint32_t>(clips.size()), phaseSeconds};
        auto behaviour = std::make_shared<bench::ClipChoiceBehaviour>(tmpl, clips);

        // The crowd on a square grid, centred across the view, rows going away from the camera.
        // Spacing: the Skeleton Root's reach, so neighbours stand apart whatever the character's size.
        bench::UnitRandom random(seed);
        std::vector<bench::ClipChoice> initial(actors);
        bench::chooseClips(initial, schedule.available(0), behaviour->durations(), 1.0, random);
        Crowd crowd;
        auto root = std::make_shared<Group>();
        const auto columns = static_cast<std::uint32_t>(std::ceil(std::sqrt(double(actors))));
        const std::uint32_t gridRows = (actors + columns - 1) / columns;
        const double spacing = std::max(0.5, 2.0 * tmpl->skeletonRootRadius());
        const double width = spacing * columns, depth = spacing * gridRows;
        for (std::uint32_t i = 0; i < actors; ++i) {
            const Vec3 at(spacing * (double(i % columns) - 0.5 * (columns - 1)), 0.0, spacing * double(i / columns));
            const std::uint32_t slot = behaviour->addActor(at, std::numbers::pi, initial[i]);  // facing the camera
            root->addChild(crowd.makeActorNode(crowd.add(tmpl, behaviour, slot)));
        }
        // Behind the first row and above it, looking at the grid's middle: the whole grid in a
        // 60-degree 16:9 view (checked on the first frame: every actor must be in the band).
        Camera camera;
        const double extent = std::max(width, depth) + 4.0 * spacing;
        camera.setPerspective(60.0 * std::numbers::pi / 180.0, 16.0 / 9.0, 0.1, 10.0 * extent);
        camera.setLookAt(Vec3(0.0, 0.9 * extent, -0.55 * extent), Vec3(0.0, 0.0, 0.5 * depth));
        // Everyone is in the band: its start is nearer than the nearest actor can be.
        const double bandStart = 0.05 * extent;

        std::vector<Run> runs;
        runs.push_back({"intermittent", "intermittent (A)", KeyPoseMode::Intermittent, nullptr, nullptr, {}});
        runs.push_back({"interpolative", "interpolative (B)", KeyPoseMode::Interpolative, nullptr, nullptr, {}});
        for (Run& r : runs) {
            KeyPoseCacheSettings s;
            s.rows = rows;
            s.mode = r.mode;
            s.keyPosesPerSecond = rate;
            r.cache = std::make_shared<KeyPoseCache>(tmpl, s);
            r.processor = std::make_unique<ActorProcessor>(crowd);
            r.processor->setThreads(threads);
            r.processor->setKeyPoseCache(r.cache);
            r.processor->setKeyPoseDistance(bandStart);
        }
        const KeyPoseCache& cache = *runs.front().cache;

        // The run: both modes on the same crowd state each frame.
        const auto frames = static_cast<std::uint32_t>(std::llround(schedule.duration() * fps));
        std::uint32_t phase = 0;
        std::vector<std::size_t> chose{actors};  // actors that chose (again) at each phase's start
        for (std::uint32_t f = 0; f < frames; ++f) {
            const double t = double(f) / double(fps);
            if (const std::uint32_t now = schedule.phaseAt(t); now != phase) {
                phase = now;
                chose.push_back(bench::chooseClips(behaviour->choices(), schedule.available(phase), behaviour->durations(), repick, random));
            }
            crowd.step(FrameContext{t, f == 0 ? 0.0 : 1.0 / fps, f, nullptr});
            for (Run& r : runs) {
                const ActorFrameStatistics& st = r.processor->processFrame(*root, camera, t);
                if (f == 0 && st.keyPoseBand != actors)
                    throw std::runtime_error(std::to_string(st.keyPoseBand) + " of " + std::to_string(actors) +
                                             " actors are in the cache's band on the first frame (the camera should see them all)");
                r.frames.push_back({f, t, phase, schedule.available(phase), st.keyPoseBand, st.keyPoseActors, st.keyPoseMisses,
                                    st.keyPoseUpdates, st.keyPosesWanted, st.keyPosesHeld});
            }
        }

        // Files.
        std::filesystem::create_directories(out);
        const auto writeFile = [&](const std::string& name, auto write) {
            std::ofstream file(out / name);
            write(file);
            if (!file) throw std::runtime_error("cannot write " + (out / name).string());
        };
        writeFile("keypose-timeline.csv", [&](std::ostream& o) {
            bench::writeTimelineCsvHeader(o);
            for (const Run& r : runs) bench::writeTimelineCsv(o, r.name, r.frames);
        });
        std::vector<std::vector<bench::TimelinePhase>> phases;
        for (const Run& r : runs) phases.push_back(bench::summarizeTimeline(r.frames));
        writeFile("keypose-timeline-phases.csv", [&](std::ostream& o) {
            o << "mode,phase,clips_available,start,end,frames,band,served_pct,min_served_pct,served_sd,misses,updates,first_updates,"
                 "later_updates,later_updates_sd,wanted,chose_again\n";
            for (std::size_t m = 0; m < runs.size(); ++m)
                for (const bench::TimelinePhase& p : phases[m]) {
                    char line[512];
                    std::snprintf(line, sizeof line, "%s,%u,%u,%.4f,%.4f,%zu,%.2f,%.3f,%.3f,%.3f,%.2f,%.3f,%llu,%.3f,%.3f,%.2f,%zu\n",
                                  runs[m].name, p.phase, p.available, p.start, p.end, p.frames, p.band, 100.0 * p.servedShare,
                                  100.0 * p.minServedShare, p.servedSd, p.misses, p.updates, static_cast<unsigned long long>(p.firstUpdates),
                                  p.laterUpdates, p.laterUpdatesSd, p.wanted, p.phase < chose.size() ? chose[p.phase] : std::size_t(0));
                    o << line;
                }
        });
        std::string clipList, firstK;
        std::uint32_t cumulative = 0;
        writeFile("keypose-timeline-clips.csv", [&](std::ostream& o) {
            o << "order,clip,duration,key_poses,first_k_key_poses\n";
            for (std::size_t k = 0; k < clips.size(); ++k) {
                const std::uint32_t n = cache.posesOf(clips[k]);
                cumulative += n;
                char line[256];
                std::snprintf(line, sizeof line, "%zu,%s,%.4f,%u,%u\n", k + 1, clipNames[k].c_str(), behaviour->durations()[k], n, cumulative);
                o << line;
                char text[128];
                std::snprintf(text, sizeof text, "%s%s %u (%.2f s)", k ? ", " : "", clipNames[k].c_str(), n, behaviour->durations()[k]);
                clipList += text;
                firstK += (k ? ", " : "") + std::to_string(cumulative);
            }
        });

        // The summary.
        std::printf("# Key-pose cache over time (seed 004 Figure 12)\n\n");
        std::printf("`%s`: %s, %u actors all in the cache's band, a cache of %u key-poses (%.3g key-poses per second of clip), "
                    "%u frames at %u fps, phases of %.3g s, re-pick share %.3g, seed %u.\n\n",
                    experiment.reproduction().c_str(), std::filesystem::path(character).filename().c_str(), actors, rows, rate, frames, fps,
                    phaseSeconds, repick, seed);
        std::printf("Clips in the order they become available, key-poses each: %s; the first k together: %s.\n\n", clipList.c_str(),
                    firstK.c_str());
        std::printf("| phase | clips | mode | key-poses wanted | served %% (mean) | served %% (lowest) | misses / frame | updates / frame | "
                    "updates, first frame | updates / frame after it (sd) |\n");
        std::printf("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
        for (std::uint32_t k = 0; k < schedule.phases(); ++k)
            for (std::size_t m = 0; m < runs.size(); ++m)
                for (const bench::TimelinePhase& p : phases[m]) {
                    if (p.phase != k) continue;
                    std::printf("| %.3g-%.3g s | %u | %s | %.1f | %s | %s | %.1f | %.2f | %llu | %.2f (%.2f) |\n", k * phaseSeconds,
                                (k + 1) * phaseSeconds, p.available, runs[m].name, p.wanted, percent(p.servedShare).c_str(),
                                percent(p.minServedShare).c_str(), p.misses, p.updates, static_cast<unsigned long long>(p.firstUpdates),
                                p.laterUpdates, p.laterUpdatesSd);
                }

        // The charts: the paper's Fig. 12 has served actors on the left axis and updates on the
        // right; VTK's charts have one, so one chart each.
        using Style = vtk::ChartSeries::Style;
        const auto series = [&](const Run& r, const std::string& name, auto value, Style style, int colour) {
            vtk::ChartSeries s;
            s.name = name;
            s.style = style;
            vtk::paletteColour(colour, s.rgb);
            for (const bench::TimelineFrame& f : r.frames) s.x.push_back(f.time), s.y.push_back(value(f));
            return s;
        };
        std::string phaseText;
        for (std::uint32_t k = 0; k < schedule.phases(); ++k) phaseText += (k ? ", " : "") + std::to_string(schedule.available(k));
        vtk::Chart served;
        char title[256];
        std::snprintf(title, sizeof title, "Actors drawn from a %u-pose cache (clips available, %.3g s each: %s)", rows, phaseSeconds,
                      phaseText.c_str());
        served.title = title;
        served.xLabel = "time (s)";
        served.yLabel = "actors";
        served.legend = vtk::Chart::Legend::Bottom;
        served.padding = 0.02;
        served.series = {series(runs[0], "served, intermittent (A)", [](const auto& f) { return double(f.served); }, Style::Line, 0),
                         series(runs[1], "served, interpolative (B)", [](const auto& f) { return double(f.served); }, Style::Line, 1),
                         series(runs[0], "actors in the band", [](const auto& f) { return double(f.band); }, Style::DashedLine, 7)};
        vtk::Chart updates;
        updates.title = "Key-poses stored in the cache each frame (updates)";
        updates.xLabel = "time (s)";
        updates.yLabel = "updates per frame";
        updates.legend = vtk::Chart::Legend::Top;
        updates.padding = 0.02;
        updates.series = {series(runs[0], "intermittent (A)", [](const auto& f) { return double(f.updates); }, Style::Line, 0),
                          series(runs[1], "interpolative (B)", [](const auto& f) { return double(f.updates); }, Style::Line, 1)};
        try {
            vtk::writeChartPng(served, (out / "keypose-timeline-served.png").string());
            vtk::writeChartPng(updates, (out / "keypose-timeline-updates.png").string());
        } catch (const std::exception& e) {
            std::fprintf(stderr, "bench_keypose_timeline: no chart (%s)\n", e.what());
        }
        std::fprintf(stderr, "written to %s\n", out.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_keypose_timeline: %s\n", e.what());
        return 1;
    }
}
