#include "throng/sim/SceneRanges.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace throng::sim {
namespace {

constexpr double kFar = 100'000.0;  // metres: no distance in a scene reaches beyond 100 km

// {section, key, lo, hi, loOpen, hiOpen, whole, unit}, in the scene guide's order.
constexpr std::array kRanges{
    SceneRange{"document", "step", 0.0, 0.5, true, false, false, "s"},
    SceneRange{"town", "blocksX", 1, 1000, false, false, true, "blocks"},
    SceneRange{"town", "blocksZ", 1, 1000, false, false, true, "blocks"},
    SceneRange{"town", "blockTiles", 1, 64, false, false, true, "tiles"},
    SceneRange{"town", "tileSize", 1.0, 100.0, false, false, false, "m"},
    SceneRange{"town", "lodScale", 0.0001, 10000.0},
    SceneRange{"walkways", "floors[].center", -kFar, kFar, false, false, false, "m"},
    SceneRange{"walkways", "floors[].size", 0.0, kFar, true, false, false, "m"},
    SceneRange{"walkways", "cellSize", 0.02, 1.0, false, false, false, "m"},
    SceneRange{"walkways", "bodyRadius", 0.1, 1.0, false, false, false, "m"},
    SceneRange{"templates", "walkClipSpeed", 0.05, 20.0, false, false, false, "m/s"},
    SceneRange{"templates", "runClipSpeed", 0.05, 20.0, false, false, false, "m/s"},
    SceneRange{"templates", "scale", 0.0001, 1000.0},
    SceneRange{"templates", "jointMinAngle", 0.0, 0.1, false, true, false, "radians"},
    SceneRange{"templates", "looks", 1, 240, false, false, true},
    SceneRange{"lod levels", "until", 0.0, kFar, true, false, false, "m"},
    SceneRange{"lod levels", "triangles", 0.0, 1.0, true, false},
    SceneRange{"actors", "count", 0, 2'000'000, false, false, true},
    SceneRange{"actors", "area.center", -kFar, kFar, false, false, false, "m"},
    SceneRange{"actors", "area.size", 0.0, kFar, true, false, false, "m"},
    SceneRange{"actors", "speed (walk)", 0.1, 10.0, false, false, false, "m/s"},
    SceneRange{"actors", "speed (flight)", 0.5, 50.0, false, false, false, "m/s"},
    SceneRange{"actors", "goal", -kFar, kFar, false, false, false, "m"},
    SceneRange{"actors", "period", -kFar, kFar, false, false, false, "m"},
    SceneRange{"actors", "altitude", 0.5, 2000.0, false, false, false, "m"},
    SceneRange{"actors", "groupSize", 1, 1000, false, false, true, "people"},
    SceneRange{"actors", "levels", 0.0, kFar, true, false, false, "m"},
    SceneRange{"actors", "priority", 0.0, 1000.0, true, false},
    SceneRange{"effects", "avoidance.quality", 0, 3, false, false, true},
    SceneRange{"effects", "avoidance.range", 1.0, 100.0, false, false, false, "agent radii"},
    SceneRange{"effects", "farUpdate.distance", 0.0, kFar, true, false, false, "m"},
    SceneRange{"effects", "farUpdate.every", 2, 1000, false, false, true, "steps"},
    SceneRange{"effects", "gaze.levels", 0.0, kFar, true, false, false, "m"},
    SceneRange{"effects", "gaze.range", 0.0, 1000.0, true, false, false, "m"},
    SceneRange{"effects", "face.levels", 0.0, kFar, true, false, false, "m"},
    SceneRange{"effects", "face.transition", 0.0, 60.0, false, false, false, "s"},
    SceneRange{"effects", "face.expressions.duration", 0.0, 3600.0, true, false, false, "s"},
    SceneRange{"effects", "face.expressions.weights", -1.0, 1.0},
    SceneRange{"effects", "blink.levels", 0.0, kFar, true, false, false, "m"},
    SceneRange{"effects", "blink.mean", 0.0, 600.0, true, false, false, "s"},
    SceneRange{"effects", "blink.spread", 0.0, 600.0, false, false, false, "s"},
    SceneRange{"effects", "blink.duration", 0.0, 2.0, true, false, false, "s"},
    SceneRange{"effects", "phrase.levels", 0.0, kFar, true, false, false, "m"},
    SceneRange{"effects", "phrase.lettersPerSecond", 0.0, 100.0, true, false, false, "letters/s"},
    SceneRange{"effects", "phrase.pause", 0.0, 600.0, false, false, false, "s"},
    SceneRange{"effects", "phrase.groupSize", 1, 1000, false, false, true, "people"},
    SceneRange{"representation", "impostorDistance", 0.0, kFar, false, false, false, "m"},
    SceneRange{"representation", "hysteresis", 0.0, 0.5},
    SceneRange{"representation", "lodScale", 0.0001, 10000.0},
    SceneRange{"representation.occlusion", "width", 8, 4096, false, false, true, "pixels"},
    SceneRange{"representation.occlusion", "height", 8, 4096, false, false, true, "pixels"},
    SceneRange{"representation.occlusion", "maxOccluders", 1, 1'000'000, false, false, true},
    SceneRange{"representation.occlusion", "rest.frames", 1, 1000, false, false, true, "frames"},
    SceneRange{"representation.occlusion", "rest.below", 0.0, 1.0},
    SceneRange{"representation.occlusion", "rest.wakeDistance", 0.0, 1'000'000.0, false, false, false, "m"},
    SceneRange{"representation.occlusion", "rest.wakeAngle", 0.0, 180.0, false, false, false, "degrees"},
    SceneRange{"representation.keyPoseCache", "rows", 1, 65535, false, false, true, "rows"},
    SceneRange{"representation.keyPoseCache", "distance", 0.0, kFar, true, false, false, "m"},
    SceneRange{"representation.keyPoseCache", "keyPosesPerSecond", 0.0, 1000.0, true, false},
    SceneRange{"camera", "fov", 0.0, 180.0, true, true, false, "degrees"},
    SceneRange{"camera", "near", 0.0, 1000.0, true, false, false, "m"},
    SceneRange{"camera", "far", 0.0, 10'000'000.0, true, false, false, "m"},
    SceneRange{"camera", "path[].time", 0.0, 1'000'000.0, false, false, false, "s"},
    SceneRange{"camera", "path[].eye", -1'000'000.0, 1'000'000.0, false, false, false, "m"},
    SceneRange{"camera", "path[].target", -1'000'000.0, 1'000'000.0, false, false, false, "m"},
};

// A bound as people write it: 2000000, 0.5, 0.0001 (never 2e+06).
std::string number(double v) {
    char text[64];
    if (v == std::floor(v) && std::fabs(v) < 1e15) std::snprintf(text, sizeof text, "%.0f", v);
    else std::snprintf(text, sizeof text, "%.10g", v);
    return text;
}

}  // namespace

std::string describeRange(const SceneRange& r) {
    if (!r.loOpen && !r.hiOpen) return "from " + number(r.lo) + " to " + number(r.hi);
    return (r.loOpen ? "above " : "from ") + number(r.lo) + (r.hiOpen ? ", below " : ", up to ") + number(r.hi);
}

bool inRange(const SceneRange& r, double v) {
    const bool aboveLo = r.loOpen ? v > r.lo : v >= r.lo;
    const bool belowHi = r.hiOpen ? v < r.hi : v <= r.hi;
    return aboveLo && belowHi;  // false for NaN
}

const SceneRange& sceneRange(std::string_view section, std::string_view key) {
    for (const SceneRange& r : kRanges)
        if (section == r.section && key == r.key) return r;
    throw std::logic_error("sceneRange: no range for '" + std::string(section) + "' key '" + std::string(key) + "'");
}

std::span<const SceneRange> sceneRanges() { return kRanges; }

}  // namespace throng::sim
