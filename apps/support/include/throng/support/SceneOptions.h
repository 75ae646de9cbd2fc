#pragma once
// The options of the tools that build a world from a scene file (throng-town, throng-vtk), declared
// alike: --scene, --actors, --seed.

#include <cstdint>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace throng::support {

/// Declares --scene FILE (an existing file; `scene` holds the default), --actors N (the scene's
/// groups scaled to N) and --seed N (overrides the scene's) on `app`, bound to the given values.
void declareSceneOptions(CLI::App& app, std::string& scene, std::optional<std::int64_t>& actors, std::optional<std::uint64_t>& seed);

}  // namespace throng::support
