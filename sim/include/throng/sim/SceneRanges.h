#pragma once
// The range every number of a scene file must lie in, in one table that the parser checks against
// and the scene guide documents (a test holds the two together). The bounds are physical (no tile of
// a kilometre, no walker at 10^6 m/s) and keep whatever the world computes from them finite.

#include <span>
#include <string>
#include <string_view>

namespace throng::sim {

/// Where one scene number must lie: from `lo` to `hi` (either end possibly excluded), in `unit`.
struct SceneRange {
    const char* section;   ///< the scene guide's table that documents it: "document", "town", "actors", ...
    const char* key;       ///< its key in that table: "tileSize", "avoidance.range", "path[].time"
    double lo;             ///< lowest value
    double hi;             ///< highest value
    bool loOpen = false;   ///< `lo` itself is refused
    bool hiOpen = false;   ///< `hi` itself is refused
    bool whole = false;    ///< integers only
    const char* unit = ""; ///< "m", "m/s", "s", ... for messages ("" for a pure number)
};

/// The range as the scene guide and the messages say it: "from 1 to 100", "above 0, up to 0.5".
std::string describeRange(const SceneRange& range);
/// Whether `value` lies in `range` (not checking `whole`).
bool inRange(const SceneRange& range, double value);
/// The range of `key` in the guide's table `section`; throws std::logic_error for one not in the table.
const SceneRange& sceneRange(std::string_view section, std::string_view key);
/// Every range, in the order of the scene guide.
std::span<const SceneRange> sceneRanges();

}  // namespace throng::sim
