#pragma once
// The command line of throng-town.

#include <cstdint>
#include <optional>
#include <string>

namespace throng::town {

/// What to run, how, and where the results go.
struct TownOptions {
    std::string scene;                      ///< scene file (default: the example's default scene)
    std::optional<std::int64_t> actors;     ///< total actors (groups scaled to it), if given
    std::int64_t frames = 600;              ///< frames to run headless
    bool framesGiven = false;               ///< --frames was given: a window also closes after them
    std::optional<std::uint64_t> seed;      ///< overrides the scene's seed
    std::string out = "town-out";           ///< folder for frames, stats.csv and summary.json
    int width = 1280, height = 720;         ///< pixels
    bool headless = false;                  ///< never open a window
    std::string gl = "auto";                ///< the GL context: auto, window, egl or osmesa (--gl)
    std::string processing = "actor";       ///< actor or traditional
    int every = 60;                         ///< headless: write a PNG every `every` frames (0: never)
    int threads = 1;                        ///< threads for the per-actor phases and the step
    bool pipeline = true;                   ///< DRAW of frame N overlaps step, APP and CULL of N+1
    bool occlusion = true;                  ///< occlusion culling when the scene declares it (off: never)
    bool keyPoseCache = true;               ///< key-pose caches when the scene declares them (off: never)
    bool looks = true;                      ///< the scene's looks (crowd diversity; off: every actor as modelled)
    bool faces = true;                      ///< the scene's faces, blinks and phrases (off: undeclared, every face neutral)
    double lodScale = 0.0;                  ///< overrides the scene's LOD scale when > 0
    double impostorDistance = -1.0;         ///< overrides the scene's impostor distance when >= 0 (0: none)
    int morphBudget = 2;                    ///< new morphed impostor cells per template and frame (0: none)
    double renderScale = 1.0;               ///< frames drawn at this fraction of width and height, scaled up
    std::string morph = "background";       ///< where impostor cells are morphed: background, grid (CPU, 4 px warp grid), cpu, gl
    std::string cellWarp = "proxy";         ///< how the CPU makes dropped key-frames: proxy (surface proxy) or lines
    double rankTimeout = 120.0;             ///< under mpirun: seconds a rank waits for another before the run stops
    std::string gather = "view";            ///< under mpirun: walkers rank 0 gathers, view (those near it) or all
    bool poseOnRanks = false;               ///< under mpirun: every rank poses the walkers it steps, rank 0 merges what they draw
    double frameBudget = 0.0;               ///< APP+CULL+DRAW a frame should stay under, ms (0: no allocator)
    std::string frameBudgetLadder;          ///< the allocator's ladder (the common accuracy CSV)
    std::string vtk;                        ///< folder for crowd data for ParaView (VTK files), empty: none
    int vtkEvery = 10;                      ///< --vtk: an actors file every K steps
};

/// Parses argv (the shared command line of the tools, throng/support/CommandLine.h). Prints the
/// help and exits with 0 on --help; `defaultLadder` is --frame-budget-ladder's default; throws std::invalid_argument naming the option on a bad one,
/// before anything is built or written.
TownOptions parseTownOptions(int argc, char** argv, const std::string& defaultScene, const std::string& defaultLadder);
/// What follows the error message of a bad command line: where the options are listed (--help).
std::string townUsage();

}  // namespace throng::town
