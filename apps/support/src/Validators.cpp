#include "throng/support/Validators.h"


#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

#include "throng/scenegraph/OutputPaths.h"
#include "throng/support/ViewGrid.h"

namespace throng::support {
namespace {

// Numbers as people read them in --help and in errors: 0.5, 1000000, 1e+09.
std::string shown(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

std::string inQuotes(const std::string& s) { return "'" + s + "'"; }

// The allowed values as --help shows them; CommandLine's help layout finds them by the bracket.
std::string allowed(const std::string& s) { return "[" + s + "]"; }

std::optional<double> finite(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (*end != '\0' || !std::isfinite(v)) return std::nullopt;
    return v;
}

CLI::Validator numberBetween(double lo, double hi, bool aboveLo, std::string description, std::string expects) {
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            const auto v = finite(text);
            if (!v || (aboveLo ? *v <= lo : *v < lo) || *v > hi) return "expects " + expects + ", got " + inQuotes(text);
            return {};
        },
        allowed(description));
}

}  // namespace

CLI::Validator wholeNumber(long long lo, long long hi) {
    const bool open = hi == std::numeric_limits<long long>::max();
    const std::string range = open ? std::to_string(lo) + " or more" : std::to_string(lo) + " to " + std::to_string(hi);
    const std::string expects = open ? "a whole number of " + range : "a whole number from " + range;
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            long long v = 0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            // A leading zero is refused: CLI11 converts integers with base 0, so "010" would be eight.
            const std::size_t digits = text.rfind('-', 0) == 0 ? 1 : 0;
            const bool leadingZero = text.size() > digits + 1 && text[digits] == '0';
            if (ec == std::errc::result_out_of_range) return "expects " + expects + ", got " + inQuotes(text) + ", which is too large";
            if (text.empty() || ec != std::errc() || end != text.data() + text.size() || leadingZero || v < lo || v > hi)
                return "expects " + expects + ", got " + inQuotes(text);
            return {};
        },
        allowed(range));
}

CLI::Validator wholeNumberFrom(long long lo) { return wholeNumber(lo, std::numeric_limits<long long>::max()); }

CLI::Validator number(double lo, double hi) {
    const std::string range = shown(lo) + " to " + shown(hi);
    return numberBetween(lo, hi, false, range, "a number from " + range);
}

CLI::Validator positiveNumber() {
    return numberBetween(0.0, std::numeric_limits<double>::max(), true, "above 0", "a number above 0");
}

CLI::Validator nonNegativeNumber() {
    return numberBetween(0.0, std::numeric_limits<double>::max(), false, "0 or more", "a number of 0 or more");
}

CLI::Validator oneOf(std::vector<std::string> choices) {
    std::string list;
    for (std::size_t i = 0; i < choices.size(); ++i) list += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            for (const std::string& c : choices)
                if (text == c) return {};
            return "expects " + list + ", got " + inQuotes(text);
        },
        allowed(list));
}

CLI::Validator existingFile() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            std::error_code ec;
            if (!std::filesystem::exists(text, ec)) return "no such file: " + inQuotes(text);
            if (!std::filesystem::is_regular_file(text, ec)) return inQuotes(text) + " is not a file";
            return {};
        },
        "");
}

CLI::Validator fileToWrite() {
    return CLI::Validator([](std::string& text) -> std::string { return problemWritingFile(text); }, "");
}

CLI::Validator folderToWrite() {
    return CLI::Validator([](std::string& text) -> std::string { return problemWritingFolder(text); }, "");
}

CLI::Validator existingFileOr(std::string keyword) {
    const CLI::Validator file = existingFile();
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            if (text == keyword) return {};
            std::string copy = text;
            if (std::string problem = file(copy); !problem.empty()) return problem + " (nor is it " + inQuotes(keyword) + ")";
            return {};
        },
        "");
}

CLI::Validator viewGrid() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            const auto g = ViewGrid::parse(text);
            if (!g || g->azimuths < 3 || g->azimuths > 256 || g->elevations < 1 || g->elevations > 64)
                return "expects AZIMUTHSxELEVATIONS with 3 to 256 azimuths and 1 to 64 elevations, e.g. 16x4, got " + inQuotes(text);
            return {};
        },
        allowed("3-256 x 1-64"));
}

}  // namespace throng::support
