#include "throng/support/ViewGrid.h"

#include <charconv>
#include <istream>
#include <ostream>
#include <string>

namespace throng::support {
namespace {

std::optional<int> wholeNumber(std::string_view text) {
    int v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return v;
}

}  // namespace

std::optional<ViewGrid> ViewGrid::parse(std::string_view text) {
    const auto x = text.find('x');
    if (x == std::string_view::npos) return std::nullopt;
    const auto a = wholeNumber(text.substr(0, x)), e = wholeNumber(text.substr(x + 1));
    if (!a || !e) return std::nullopt;
    return ViewGrid{*a, *e};
}

std::istream& operator>>(std::istream& in, ViewGrid& grid) {
    std::string text;
    in >> text;
    if (const auto g = ViewGrid::parse(text)) grid = *g;
    else in.setstate(std::ios::failbit);
    return in;
}

std::ostream& operator<<(std::ostream& out, const ViewGrid& grid) { return out << grid.azimuths << 'x' << grid.elevations; }

}  // namespace throng::support
