// bench_keypose_selection: seed 004's Figure 7. For each cache size, how many actors the cache
// serves when its key-poses are chosen by the greedy selection (§4.2), exactly (§4.1, GLPK's
// branch and bound), naively (key-poses 0 .. n-1) or at random, averaged over many frames; the
// gap between greedy and exact; the time each selection takes. Frames are the paper's random
// instances (30 characters, 22 key-poses, normally distributed) or demands read from a CSV file
// (--demands FILE, columns frame,a,b,actors), e.g. recorded from a crowd.
// Writes keypose-selection.csv, keypose-selection.png and keypose-selection-time.png (the plots
// through VTK: run under xvfb-run -a without a display) and prints a Markdown table.
//
//   bench_keypose_selection [--out DIR] [--frames 200] [--characters 30] [--poses 22] [--sd S]
//                           [--next 0.5] [--intermittent] [--seed 1] [--demands FILE]
//                           [--capacities 1,2,...] [--time-limit 10]
// Exit codes: 0 done, 1 a measurement failed (the message says why), 2 a bad command line.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "KeyPoseStudy.h"
#include "throng/bench/Experiment.h"
#include "throng/vtk/Chart.h"

using namespace throng;

int main(int argc, char** argv) {
    std::string outText = "keypose-selection";
    std::string demandsFile;
    std::uint32_t frames = 200, characters = 30, poses = 22, seed = 1;
    double sd = 0.0, next = 0.5, timeLimit = 10.0;
    bool intermittent = false;
    std::vector<std::uint32_t> capacities;
    // Not a frame-level experiment (no world, no ticks): the harness gives it its command line only.
    bench::Experiment experiment("bench_keypose_selection",
                                 "Seed 004 Figure 7: actors a key-pose cache serves against its size, for the greedy, exact (GLPK),\n"
                                 "first-n and random-n selections, with the greedy/exact gap and the solve times. Writes\n"
                                 "keypose-selection.csv and .png (the plots through VTK: without a display, run under xvfb-run -a).",
                                 0, {});
    CLI::App& app = experiment.app();
    app.add_option("--out", outText, "folder for the report")->type_name("DIR")->check(bench::folderToWrite());
    app.add_option("--demands", demandsFile, "demands to measure instead of random instances (CSV: frame,a,b,actors)")
        ->type_name("FILE")
        ->check(CLI::ExistingFile);
    app.add_option("--frames", frames, "random instances (frames)")->type_name("N")->check(CLI::Range(1, 1000000));
    app.add_option("--characters", characters, "actors per random instance")->type_name("N")->check(CLI::Range(1, 1000000));
    app.add_option("--poses", poses, "key-poses of a random instance (with --demands: the key-poses first-n and random-n choose from; default the largest named + 1)")
        ->type_name("N")
        ->check(CLI::Range(2, 1 << 24));
    app.add_option("--sd", sd, "standard deviation of the normal pose distribution, in poses")
        ->type_name("X")
        ->check(bench::finiteNumber(1e-9, 1e9))
        ->default_str("poses / 6");
    app.add_option("--next", next, "probability that an actor's second pose is the next one (else a random one)")
        ->type_name("P")
        ->check(bench::finiteNumber(0.0, 1.0));
    app.add_flag("--intermittent", intermittent, "one pose per actor (seed 004 §3) instead of two");
    app.add_option("--seed", seed, "seed of the first random instance")->type_name("N")->check(CLI::Range(std::uint32_t(0), std::uint32_t(4000000000u)));
    app.add_option("--capacities", capacities, "cache sizes to measure")
        ->type_name("N,N,...")
        ->delimiter(',')
        ->check(CLI::Range(0, 1 << 24))
        ->default_str("1 to the number of key-poses");
    app.add_option("--time-limit", timeLimit, "seconds allowed to each exact solve")->type_name("S")->check(bench::finiteNumber(1e-9, 1e9));
    if (const auto code = experiment.parse(argc, argv)) return *code;
    const bool posesGiven = app.count("--poses") > 0;
    try {
        const std::filesystem::path out = outText;
        bench::KeyPoseFrames instances;
        std::string source, shortSource;  // the whole description for the table, a short one for the chart
        bench::KeyPoseStudyOptions options;
        options.exactTimeLimit = timeLimit;
        if (!demandsFile.empty()) {
            std::ifstream in(demandsFile);
            if (!in) throw std::runtime_error("cannot open " + demandsFile);
            instances = bench::readKeyPoseDemandsCsv(in, demandsFile);
            if (instances.empty()) throw std::runtime_error(demandsFile + ": no demands");
            if (posesGiven) options.poseCount = poses;
            source = std::to_string(instances.size()) + " frames from " + demandsFile;
            shortSource = std::to_string(instances.size()) + " frames of " + std::filesystem::path(demandsFile).filename().string();
        } else {
            if (sd <= 0.0) sd = poses / 6.0;
            instances = bench::randomKeyPoseFrames(frames, characters, poses, sd, next, intermittent, seed);
            options.poseCount = poses;
            char text[256];
            std::snprintf(text, sizeof text, "%u random frames: %u characters, %u key-poses, normal (sd %.2f poses), %s", frames, characters,
                          poses, sd,
                          intermittent ? "one pose each" : (next >= 1.0 ? "next pose" : next <= 0.0 ? "random second pose" : "second pose the next one or random"));
            source = text;
            shortSource = std::to_string(characters) + " characters, " + std::to_string(poses) + " key-poses, " + std::to_string(frames) +
                          " frames";
        }
        if (capacities.empty())
            for (std::uint32_t c = 1, n = bench::keyPoseCount(instances, options.poseCount); c <= n; ++c) capacities.push_back(c);
        const std::vector<bench::KeyPoseStudyRow> rows = bench::studyKeyPoseSelection(instances, capacities, options);

        std::filesystem::create_directories(out);
        {
            std::ofstream csv(out / "keypose-selection.csv");
            bench::writeKeyPoseStudyCsv(csv, rows);
            if (!csv) throw std::runtime_error("cannot write " + (out / "keypose-selection.csv").string());
        }
        std::printf("# Key-pose selection (seed 004 Figure 7)\n\n%s; exact: GLPK, %.3g s limit per solve.\n\n", source.c_str(), timeLimit);
        std::printf("| cache | actors | greedy | exact | first-n | random-n | greedy/exact | worst frame | frames greedy < exact | "
                    "unproven | greedy us | exact us (mean) | exact us (max) |\n");
        std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        for (const bench::KeyPoseStudyRow& r : rows)
            std::printf("| %u | %.2f | %.2f | %.2f | %.2f | %.2f | %.4f | %.3f | %zu / %zu | %zu | %.2f | %.0f | %.0f |\n", r.capacity, r.actors,
                        r.greedy, r.exact, r.firstN, r.randomN, r.greedyOverExact, r.worstGreedyOverExact, r.greedyBelowExact, r.frames,
                        r.exactUnproven, r.greedyMicroseconds, r.exactMicrosecondsMean, r.exactMicrosecondsMax);

        vtk::Chart served;
        served.title = "Actors served by a key-pose cache (" + shortSource + ")";
        served.xLabel = "cache size (key-poses)";
        served.yLabel = "actors served (mean per frame)";
        served.legend = vtk::Chart::Legend::Bottom;
        const auto series = [&](const std::string& name, auto value, vtk::ChartSeries::Style style, int colour) {
            vtk::ChartSeries s;
            s.name = name;
            s.style = style;
            vtk::paletteColour(colour, s.rgb);
            for (const bench::KeyPoseStudyRow& r : rows) s.x.push_back(r.capacity), s.y.push_back(value(r));
            return s;
        };
        using Style = vtk::ChartSeries::Style;
        served.series = {series("exact (GLPK)", [](const auto& r) { return r.exact; }, Style::LineAndPoints, 0),
                         series("greedy (seed 004 4.2)", [](const auto& r) { return r.greedy; }, Style::LineAndPoints, 1),
                         series("first n key-poses", [](const auto& r) { return r.firstN; }, Style::LineAndPoints, 2),
                         series("n random key-poses", [](const auto& r) { return r.randomN; }, Style::LineAndPoints, 3),
                         series("all actors", [](const auto& r) { return r.actors; }, Style::DashedLine, 7)};
        vtk::Chart time;
        time.title = "Time to choose the key-poses";
        time.xLabel = "cache size (key-poses)";
        time.yLabel = "microseconds per frame";
        time.logY = true;
        time.legend = vtk::Chart::Legend::Bottom;
        time.series = {series("exact (GLPK), mean", [](const auto& r) { return r.exactMicrosecondsMean; }, Style::LineAndPoints, 0),
                       series("exact (GLPK), slowest", [](const auto& r) { return r.exactMicrosecondsMax; }, Style::DashedLine, 0),
                       series("greedy, mean", [](const auto& r) { return r.greedyMicroseconds; }, Style::LineAndPoints, 1)};
        try {
            vtk::writeChartPng(served, (out / "keypose-selection.png").string());
            vtk::writeChartPng(time, (out / "keypose-selection-time.png").string());
        } catch (const std::exception& e) {
            std::fprintf(stderr, "no plot (%s); run under xvfb-run -a\n", e.what());
        }
        std::fprintf(stderr, "written to %s\n", out.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_keypose_selection: %s\n", e.what());
        return 1;
    }
}
