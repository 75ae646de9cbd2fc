#pragma once
// The views of an impostor hemisphere as the tools write them: "16x4", azimuths around by rings of
// elevation. Streamable, so that a CLI11 option can hold one and show its default.

#include <iosfwd>
#include <optional>
#include <string_view>

namespace throng::support {

/// Azimuths by elevation rings of the view hemisphere an impostor is baked on.
struct ViewGrid {
    int azimuths = 16;   ///< views around
    int elevations = 4;  ///< rings from the horizon up

    /// Reads "AxE" (two decimal whole numbers around an 'x'); std::nullopt when `text` is not of
    /// that form. Ranges are the caller's to check.
    static std::optional<ViewGrid> parse(std::string_view text);
};

/// Reads "AxE"; sets failbit when the text is not of that form.
std::istream& operator>>(std::istream& in, ViewGrid& grid);
/// Writes "AxE".
std::ostream& operator<<(std::ostream& out, const ViewGrid& grid);

}  // namespace throng::support
