#include "TownOptions.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace throng::town {
namespace {

std::int64_t integer(const std::string& flag, const char* v, std::int64_t lo, std::int64_t hi) {
    if (!v) throw std::invalid_argument(flag + " needs a value");
    char* end = nullptr;
    const long long x = std::strtoll(v, &end, 10);
    if (*end != '\0' || x < lo || x > hi)
        throw std::invalid_argument(flag + " expects a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got '" + v + "'");
    return x;
}

}  // namespace

std::string townUsage() {
    return "usage: throng-town [options]\n"
           "  --scene FILE        scene file (JSON; default: the town example's default scene)\n"
           "  --actors N          total actors, the scene's groups scaled to it\n"
           "  --frames N          frames to run headless (default 600 = 10 s); in a window, quit after N\n"
           "  --seed N            overrides the scene's seed\n"
           "  --out DIR           frames, stats.csv and summary.json go here (default town-out)\n"
           "  --width W --height H   image size (default 1280 x 720)\n"
           "  --headless          never open a window (the default when there is no display)\n"
           "  --processing actor|traditional   how the scene is processed (default actor)\n"
           "  --every K           headless: a PNG frame every K frames (default 60; 0: none)\n"
           "  --threads N         threads for the simulation step and the per-actor phases (default 1)\n"
           "  --pipeline on|off   DRAW of frame N overlaps the step, APP and CULL of frame N+1 (default on)\n"
           "  --lod-scale X       multiplies every LOD distance (default: the scene's)\n"
           "  --impostor-distance D   actors beyond D metres are drawn as impostors (0: never; default: the scene's)\n"
           "In a window: mouse drag looks, W/A/S/D/Q/E move, Tab path/free camera, Space pause,\n"
           "+/- LOD scale, C shrink the culling pyramid (watch culling at work), P processing, Esc quit.\n";
}

TownOptions parseTownOptions(int argc, char** argv, const std::string& defaultScene) {
    TownOptions o;
    o.scene = defaultScene;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
        if (a == "--help" || a == "-h") {
            std::fputs(townUsage().c_str(), stdout);
            std::exit(0);
        } else if (a == "--scene") {
            const char* v = value();
            if (!v) throw std::invalid_argument("--scene needs a file");
            o.scene = v;
        } else if (a == "--actors") {
            o.actors = integer(a, value(), 0, 2'000'000);
        } else if (a == "--frames") {
            o.frames = integer(a, value(), 1, 100'000'000);
            o.framesGiven = true;
        } else if (a == "--seed") {
            o.seed = std::uint64_t(integer(a, value(), 0, INT64_MAX));
        } else if (a == "--out") {
            const char* v = value();
            if (!v) throw std::invalid_argument("--out needs a folder");
            o.out = v;
        } else if (a == "--width") {
            o.width = int(integer(a, value(), 16, 8192));
        } else if (a == "--height") {
            o.height = int(integer(a, value(), 16, 8192));
        } else if (a == "--headless") {
            o.headless = true;
        } else if (a == "--processing") {
            const char* v = value();
            if (!v || (std::string(v) != "actor" && std::string(v) != "traditional"))
                throw std::invalid_argument("--processing expects 'actor' or 'traditional'");
            o.processing = v;
        } else if (a == "--every") {
            o.every = int(integer(a, value(), 0, 1'000'000));
        } else if (a == "--threads") {
            o.threads = int(integer(a, value(), 1, 256));
        } else if (a == "--pipeline") {
            const char* v = value();
            if (!v || (std::string(v) != "on" && std::string(v) != "off"))
                throw std::invalid_argument("--pipeline expects 'on' or 'off'");
            o.pipeline = std::string(v) == "on";
        } else if (a == "--lod-scale") {
            const char* v = value();
            char* end = nullptr;
            o.lodScale = v ? std::strtod(v, &end) : 0.0;
            if (!v || *end != '\0' || !std::isfinite(o.lodScale) || o.lodScale <= 0.0)
                throw std::invalid_argument("--lod-scale expects a positive number");
        } else if (a == "--impostor-distance") {
            const char* v = value();
            char* end = nullptr;
            o.impostorDistance = v ? std::strtod(v, &end) : -1.0;
            if (!v || *end != '\0' || !std::isfinite(o.impostorDistance) || o.impostorDistance < 0.0)
                throw std::invalid_argument("--impostor-distance expects a distance in metres (0: no impostors)");
        } else {
            throw std::invalid_argument("unknown option '" + a + "'");
        }
    }
    return o;
}

}  // namespace throng::town
