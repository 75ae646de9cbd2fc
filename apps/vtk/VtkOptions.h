#pragma once
// The command line of throng-vtk.

#include <cstdint>
#include <optional>
#include <string>

namespace throng::vtkapp {

/// What to show, and where a screenshot goes.
struct VtkOptions {
    std::string scene;                    ///< scene file (default: the town example's default scene)
    std::optional<std::int64_t> actors;   ///< total actors (groups scaled to it), if given
    std::optional<std::uint64_t> seed;    ///< overrides the scene's seed
    std::string screenshot;               ///< write a PNG here and exit (empty: open a window)
    std::int64_t frames = 60;             ///< --screenshot: simulation steps before the picture
    bool framesGiven = false;             ///< --frames was given: a window also closes after them
    int width = 1280, height = 720;       ///< pixels
    /// Who draws the crowd: "vtk" (a VTK mapper, meshes only) or "throng" (Throng's renderer in
    /// VTK's context: textures, and the scene's key-pose caches and impostors).
    std::string draw = "vtk";
};

/// Parses argv (the shared command line of the tools, throng/support/CommandLine.h). Prints the
/// help and exits with 0 on --help; throws std::invalid_argument naming the option on a bad one,
/// before anything is built or written.
VtkOptions parseVtkOptions(int argc, char** argv, const std::string& defaultScene);
/// What follows the error message of a bad command line: where the options are listed (--help).
std::string vtkUsage();

}  // namespace throng::vtkapp
