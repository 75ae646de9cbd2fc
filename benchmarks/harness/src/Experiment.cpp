#include "throng/bench/Experiment.h"

#include "throng/render/ContextFactory.h"
#include "throng/scenegraph/OutputPaths.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace throng::bench {
namespace {

// --help as the tools lay it out: "--frames N   measured ticks per camera (INT in [1 - 1000000])
// (default: 2)": the value's name beside the option, its checks and default after the description.
class HelpLayout : public CLI::Formatter {
public:
    std::string make_option_opts(const CLI::Option* opt) const override {
        if (opt->get_type_size() == 0 || opt->get_positional()) return {};
        const std::string type = opt->get_type_name();
        return " " + type.substr(0, type.find(':'));
    }
    std::string make_option_desc(const CLI::Option* opt) const override {
        std::string out = opt->get_description();
        const std::string type = opt->get_type_name();
        const auto colon = type.find(':');
        const std::string name = type.substr(0, colon);
        if (colon != std::string::npos && type.substr(colon + 1) != name) out += " (" + type.substr(colon + 1) + ")";
        if (!opt->get_default_str().empty()) out += " (default: " + opt->get_default_str() + ")";
        return out;
    }
};

// A number as people write it: 0.5, 1e+06.
std::string shown(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

}  // namespace

Experiment::Experiment(std::string program, std::string description, unsigned options, ExperimentSpec defaults, ExperimentNames names)
    : program_(std::move(program)), options_(options), spec_(std::move(defaults)), names_(std::move(names)), app_(std::move(description), program_) {
    app_.formatter(std::make_shared<HelpLayout>());
    app_.option_defaults()->always_capture_default();
    // A single-valued option given twice is refused (CLI11's default), rather than one value silently winning.
    if (options & kScene) app_.add_option("--scene", spec_.scene, "scene file")->type_name("FILE")->check(CLI::ExistingFile);
    if (options & kActorList)
        app_.add_option("--actors", spec_.actors, "actor counts (the scene's groups scaled to each)")
            ->delimiter(',')->type_name("N,N,...")->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
            ->check(CLI::Range(names_.minActors, names_.maxActors));
    if (options & kActorCount) {
        actorCount_ = spec_.actors.empty() ? 0 : spec_.actors.front();
        app_.add_option("--actors", actorCount_, "actors (0: the scene's own count)")->type_name("N")->check(CLI::Range(std::int64_t(0), names_.maxActors));
    }
    if (options & kCameras)
        app_.add_option("--cameras", spec_.cameras, "cameras")->delimiter(',')->type_name("NAME,...")
            ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(CLI::IsMember({"street", "overview"}));
    if (options & kFrames) app_.add_option(names_.frames, spec_.frames, names_.framesHelp)->type_name("N")->check(CLI::Range(names_.minFrames, 1'000'000));
    if (options & kWarmup) app_.add_option("--warmup", spec_.warmup, "ticks stepped before measuring")->type_name("N")->check(CLI::Range(0, 1'000'000));
    if (options & kImageSize) {
        app_.add_option("--width", spec_.width, "image width")->type_name("W")->check(CLI::Range(16, 8192));
        app_.add_option("--height", spec_.height, "image height")->type_name("H")->check(CLI::Range(16, 8192));
        app_.add_option("--gl", spec_.gl, "GL context: auto (EGL on a GPU, else OSMesa, else EGL surfaceless), egl (a GPU, else "
                                          "Mesa's surfaceless platform) or osmesa")
            ->type_name("KIND")
            ->check(CLI::IsMember({"auto", "egl", "osmesa"}));
    }
    if (options & kThreads) app_.add_option("--threads", spec_.threads, "threads of the step")->type_name("N")->check(CLI::Range(1, 256));
    if (options & kStarts)
        app_.add_option("--starts", spec_.starts, "camera path times (s) where measured runs start")->delimiter(',')->type_name("T,T,...")
            ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(finiteNumber(0.0, 1e6));
    if (options & kErrorEvery) app_.add_option("--error-every", spec_.errorEvery, names_.errorEveryHelp)->type_name("N")->check(CLI::Range(1, 1'000'000));
    if (options & kCsv) app_.add_option("--csv", spec_.csv, names_.csvHelp)->type_name("FILE")->check(fileToWrite());
    if (options & kAccuracyCsv) app_.add_option("--accuracy-csv", spec_.accuracyCsv, names_.accuracyCsvHelp)->type_name("FILE")->check(fileToWrite());
    if (options & kMarkdown) app_.add_option("--markdown", spec_.markdown, "also write the report as Markdown")->type_name("FILE")->check(fileToWrite());
    if (options & kPlots) app_.add_option("--plots", spec_.plots, "write the figures as PNG into DIR (needs a display: xvfb-run -a)")->type_name("DIR")->check(folderToWrite());
    outputs_ = {"--csv", "--accuracy-csv", "--markdown", "--plots"};
}

std::optional<int> Experiment::parse(int argc, char** argv) {
    try {
        app_.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app_.exit(e);  // --help: printed on stdout
        std::fprintf(stderr, "%s: %s\nRun '%s --help' for the options.\n", program_.c_str(), e.what(), program_.c_str());
        return kUsageError;
    }
    if (options_ & kActorCount) spec_.actors = {actorCount_};
    reproduction_ = program_;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        bool output = false;
        for (const std::string& o : outputs_) {
            if (arg == o) output = true, ++i;
            else if (arg.rfind(o + "=", 0) == 0) output = true;
        }
        if (!output) reproduction_ += " " + std::string(arg);
    }
    return std::nullopt;
}

void Experiment::progress(const std::string& message) const { std::fprintf(stderr, "%s: %s\n", program_.c_str(), message.c_str()); }

void Experiment::fail(const std::string& why) const {
    std::fprintf(stderr, "%s: %s\n", program_.c_str(), why.c_str());
    std::exit(kFailure);
}

std::shared_ptr<GlContext> experimentContext(const ExperimentSpec& spec) {
    return createContext({.width = spec.width, .height = spec.height, .window = false, .api = glApiFromName(spec.gl)});
}

void writeWhole(const std::string& path, const std::string& text) {
    const std::string part = path + ".part";
    {
        std::ofstream out(part, std::ios::binary | std::ios::trunc);
        if (!out) throw std::runtime_error("cannot write " + path);
        out << text;
        out.close();
        if (!out) {
            std::filesystem::remove(part);
            throw std::runtime_error("cannot write " + path + " (disk full?)");
        }
    }
    std::error_code ec;
    std::filesystem::rename(part, path, ec);
    if (ec) {
        std::filesystem::remove(part);
        throw std::runtime_error("cannot write " + path + ": " + ec.message());
    }
}

CLI::Validator finiteNumber(double lo, double hi) {
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
                return "expects a number from " + shown(lo) + " to " + shown(hi) + ", got '" + text + "'";
            return {};
        },
        "[" + shown(lo) + " to " + shown(hi) + "]");
}

CLI::Validator fileToWrite() {
    return CLI::Validator([](std::string& text) -> std::string { return problemWritingFile(text); }, "FILE");
}

CLI::Validator folderToWrite() {
    return CLI::Validator([](std::string& text) -> std::string { return problemWritingFolder(text); }, "DIR");
}

}  // namespace throng::bench
