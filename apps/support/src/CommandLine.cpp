#include "throng/support/CommandLine.h"

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace throng::support {
namespace {

// --help laid out the same for every tool: "--threads N   what it does [1 to 256] (default: 1)".
// CLI11 appends the validators' descriptions to the type name ("N:[1 to 256]", Validators.h writes
// them in brackets) and the default after an '=' beside the option; here the type stays beside the
// option and the allowed values and the default go after the description.
class HelpFormatter : public CLI::Formatter {
public:
    std::string make_option_opts(const CLI::Option* opt) const override {
        if (opt->get_type_size() == 0 || opt->get_positional()) return {};  // a flag, or a positional named by its value
        std::string out = " " + split(opt).first;
        if (opt->get_required()) out += " (required)";
        return out;
    }
    std::string make_option_desc(const CLI::Option* opt) const override {
        std::string out = opt->get_description();
        if (const std::string allowed = split(opt).second; !allowed.empty()) out += " " + allowed;
        if (!opt->get_default_str().empty()) out += " (default: " + opt->get_default_str() + ")";
        return out;
    }

private:
    // The type name as declared, and the allowed values ("[1 to 256]", or several side by side).
    static std::pair<std::string, std::string> split(const CLI::Option* opt) {
        const std::string t = opt->get_type_name();
        const auto at = t.find(":[");
        if (at == std::string::npos) return {t, {}};
        std::string allowed = t.substr(at + 1);
        for (auto p = allowed.find(":["); p != std::string::npos; p = allowed.find(":[", p)) allowed[p] = ' ';
        return {t.substr(0, at), allowed};
    }
};

// CLI11's message for an error, reworded where it speaks of types rather than of the option.
std::string problem(const CLI::ParseError& e) {
    std::string what = e.what();
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) {
        // "--width: 1 required N missing": the option was the last word, with no value after it.
        const auto colon = what.find(": ");
        if (colon != std::string::npos && what.find(" required ", colon) != std::string::npos &&
            what.size() >= 8 && what.compare(what.size() - 8, 8, " missing") == 0)
            return what.substr(0, colon) + ": needs a value";
        // "--frames: At Most 1 required but received 2": the option was repeated.
        constexpr std::string_view kRepeated = "At Most 1 required but received ";
        const auto received = what.find(kRepeated);
        if (colon != std::string::npos && received != std::string::npos)
            return what.substr(0, colon) + ": given " + std::to_string(std::atoi(what.c_str() + received + kRepeated.size())) +
                   " times (give it once)";
    }
    if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
        // "The following argument was not expected: --bogus".
        const auto colon = what.find(": ");
        const std::string rest = colon == std::string::npos ? what : what.substr(colon + 2);
        if (rest.find(' ') == std::string::npos)
            return rest.rfind('-', 0) == 0 ? "unknown option '" + rest + "'" : "unexpected argument '" + rest + "'";
        return "unexpected arguments: " + rest;
    }
    return what;
}

}  // namespace

CommandLine::CommandLine(std::string name, std::string description) : name_(std::move(name)), app_(std::move(description), name_) {
    app_.formatter(std::make_shared<HelpFormatter>());
    app_.set_help_flag("-h,--help", "print this help and exit");
    // Every option shows its default in --help (an option whose default means "whatever the scene
    // says" replaces it with default_str), and an option given twice is refused: which of two
    // values was meant cannot be known (a script that appends its own --frames to a user's).
    app_.option_defaults()->always_capture_default()->multi_option_policy(CLI::MultiOptionPolicy::Throw);
}

bool CommandLine::parseOrThrow(int argc, char** argv) {
    try {
        app_.parse(argc, argv);
        return true;
    } catch (const CLI::CallForHelp&) {
        return false;
    } catch (const CLI::ParseError& e) {
        throw std::invalid_argument(problem(e));
    }
}

std::optional<int> CommandLine::parse(int argc, char** argv) {
    try {
        if (parseOrThrow(argc, argv)) return std::nullopt;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s: %s\n%s", name_.c_str(), e.what(), hint(name_).c_str());
        return kUsageError;
    }
    std::fputs(help().c_str(), stdout);
    return 0;
}

void CommandLine::parseOrExitOnHelp(const std::string& name, const std::string& description, int argc, char** argv,
                                    const std::function<void(CommandLine&)>& declare,
                                    const std::function<void(CommandLine&)>& parsed) {
    std::string text;
    {
        CommandLine cl(name, description);
        declare(cl);
        if (cl.parseOrThrow(argc, argv)) {
            if (parsed) parsed(cl);
            return;
        }
        text = cl.help();
    }
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
    std::exit(0);
}

std::string CommandLine::help() const { return app_.help(); }

std::string CommandLine::hint(const std::string& name) { return "Run '" + name + " --help' for the options.\n"; }

}  // namespace throng::support
