#pragma once
// The command line of a Throng tool: CLI11 set up the same way for every tool, so that they all
// show their defaults on --help, take the last value of a repeated option, and reject a bad
// command line alike: one line "tool: problem naming the option", a pointer to --help, exit code 2,
// before the tool has done anything.

#include <functional>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace throng::support {

/// A tool's command line. Declare the options on app(), then call parse() first thing in main.
class CommandLine {
public:
    /// Exit code of a tool given a bad command line.
    static constexpr int kUsageError = 2;

    /// The command line of the tool `name`, introduced by `description` at the top of --help.
    CommandLine(std::string name, std::string description);

    /// Where the tool declares its options (CLI11).
    CLI::App& app() { return app_; }

    /// Parses argv. std::nullopt: go on and run. Otherwise the tool returns the code given, after
    /// this printed why: 0 after --help (the help on stdout), kUsageError after a bad command line.
    std::optional<int> parse(int argc, char** argv);

    /// Parses argv without printing: false when --help was asked for. Throws std::invalid_argument
    /// with the problem, naming the option, on a bad command line (for tools that report errors
    /// themselves; print it as "tool: problem" followed by hint()).
    bool parseOrThrow(int argc, char** argv);

    /// For tools that parse in a function returning their options: makes the command line of `name`,
    /// lets `declare` put the options on it, parses argv, then calls `parsed` (e.g. to ask which
    /// options were given). On --help prints the help and exits with 0 (after destroying the command
    /// line); throws std::invalid_argument naming the option on a bad command line.
    static void parseOrExitOnHelp(const std::string& name, const std::string& description, int argc, char** argv,
                                  const std::function<void(CommandLine&)>& declare,
                                  const std::function<void(CommandLine&)>& parsed = {});

    /// The --help text: usage, every option with its allowed values and default, the footer.
    std::string help() const;

    /// The line printed after an error: where the options are listed.
    static std::string hint(const std::string& name);

private:
    std::string name_;
    CLI::App app_;
};

}  // namespace throng::support
