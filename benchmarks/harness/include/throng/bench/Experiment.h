#pragma once
// The experiment harness of the frame-level benchmarks: one option set (scene, actors, cameras,
// measured and warm-up ticks, image size, threads, output files) declared the same way for every
// benchmark, checked before anything runs, and the way an experiment reports: progress and
// failures as "program: ...", its own command line in its report, outputs written whole.
//
// A benchmark declares its variants on app() beside the common options, calls parse() first thing
// in main, then runs its variants on the identical stepped state (SameState.h) and writes its rows
// through a ResultTable (ResultTable.h).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "throng/render/GlContext.h"

namespace throng::bench {

/// The common options' values; an experiment's defaults go in before parse().
struct ExperimentSpec {
    std::string scene{};                         ///< scene file
    std::vector<std::int64_t> actors{};          ///< actor counts, each run in turn (0: the scene's own count)
    std::vector<std::string> cameras{};          ///< "street", "overview"
    int frames = 20;                           ///< measured ticks (per camera, per start: the experiment says)
    int warmup = 60;                           ///< ticks stepped before measuring
    int width = 1280;                          ///< image width
    int height = 720;                          ///< image height
    std::string gl = "auto";                     ///< the GL context (--gl, with the image size): auto, egl or osmesa
    int threads = 1;                           ///< threads of the step
    std::vector<double> starts{};              ///< camera path times (s) where measured runs start
    int errorEvery = 4;                        ///< measured ticks between accuracy measurements
    std::string csv{};                           ///< the experiment's own CSV
    std::string accuracyCsv{};                   ///< the common accuracy CSV (throng/sim/AccuracyCsv.h)
    std::string markdown{};                      ///< the report as Markdown
    std::string plots{};                         ///< folder for PNG figures
};

/// Which common options an experiment takes (bits of Experiment's `options`).
enum ExperimentOption : unsigned {
    kScene = 1u << 0,        ///< --scene FILE
    kActorList = 1u << 1,    ///< --actors N,N,...
    kActorCount = 1u << 2,   ///< --actors N (one count; 0: the scene's own)
    kCameras = 1u << 3,      ///< --cameras street,overview
    kFrames = 1u << 4,       ///< the measured ticks (named by ExperimentNames::frames)
    kWarmup = 1u << 5,       ///< --warmup N
    kImageSize = 1u << 6,    ///< --width W --height H --gl KIND
    kThreads = 1u << 7,      ///< --threads N
    kCsv = 1u << 8,          ///< --csv FILE
    kAccuracyCsv = 1u << 9,  ///< --accuracy-csv FILE
    kMarkdown = 1u << 10,    ///< --markdown FILE
    kPlots = 1u << 11,       ///< --plots DIR
    kStarts = 1u << 12,      ///< --starts T,T,... (runs along the camera path)
    kErrorEvery = 1u << 13,  ///< --error-every N
};

/// How an experiment words its common options where they differ in meaning.
struct ExperimentNames {
    std::string frames = "--frames";                     ///< the measured ticks' option
    std::string framesHelp = "measured ticks per camera"; ///< and what they are
    std::int64_t minActors = 1;                          ///< the smallest actor count accepted
    std::int64_t maxActors = 10'000'000;                 ///< the largest
    int minFrames = 1;                                   ///< the fewest measured ticks accepted
    std::string csvHelp = "also write the rows as CSV";  ///< what --csv writes
    std::string accuracyCsvHelp = "write the rows in the common accuracy CSV";  ///< what --accuracy-csv writes
    std::string errorEveryHelp = "ticks between image comparisons";  ///< what --error-every measures
};

/// One frame-level experiment's command line and reporting.
class Experiment {
public:
    /// Exit code after a bad command line.
    static constexpr int kUsageError = 2;
    /// Exit code after a failed run.
    static constexpr int kFailure = 1;

    /// The experiment `program`, introduced by `description` in --help, taking the common options
    /// `options` (ExperimentOption bits) with `defaults`.
    Experiment(std::string program, std::string description, unsigned options, ExperimentSpec defaults, ExperimentNames names = {});

    /// Where the experiment declares its own options (its variants).
    CLI::App& app() { return app_; }
    /// Parses argv. std::nullopt: run. Otherwise main returns the code given: 0 after --help (printed),
    /// kUsageError after a bad command line (one line naming the option, and where --help is).
    std::optional<int> parse(int argc, char** argv);
    /// The common options' values.
    const ExperimentSpec& spec() const { return spec_; }
    /// The program's name.
    const std::string& program() const { return program_; }

    /// Marks an option of the experiment's own as naming an output file, so reproduction() leaves it out.
    void markOutput(std::string option) { outputs_.push_back(std::move(option)); }
    /// The command line as given, less the options naming output files: what a report quotes so a
    /// reader can run it again ("program --frames 4 ...").
    const std::string& reproduction() const { return reproduction_; }
    /// Prints "program: message" on stderr (progress of a long run).
    void progress(const std::string& message) const;
    /// Prints "program: why" on stderr and exits with kFailure.
    [[noreturn]] void fail(const std::string& why) const;

private:
    std::string program_;
    unsigned options_ = 0;
    ExperimentSpec spec_;
    ExperimentNames names_;
    CLI::App app_;
    std::int64_t actorCount_ = 0;
    std::vector<std::string> outputs_;
    std::string reproduction_;
};

/// The off-screen context an experiment draws in: `spec.gl`'s kind at spec.width x spec.height.
/// Throws ContextUnavailable (what is missing) when a kind asked for by name cannot be made.
std::shared_ptr<GlContext> experimentContext(const ExperimentSpec& spec);

/// Writes `text` to `path` whole or not at all: into "path.part", then renamed. Throws
/// std::runtime_error naming the path when it cannot.
void writeWhole(const std::string& path, const std::string& text);

/// CLI11 checks the experiments share that CLI11 lacks: a finite number from `lo` to `hi` (NaN and
/// infinities refused), and a file to write (its folder exists; the path is not a folder).
CLI::Validator finiteNumber(double lo, double hi);
/// A file the experiment may write (problemWritingFile: its folder exists and can be written into,
/// and the path is not a folder).
CLI::Validator fileToWrite();
/// A folder to write into (problemWritingFolder: existing and writable, or creatable; nothing made).
CLI::Validator folderToWrite();

}  // namespace throng::bench
