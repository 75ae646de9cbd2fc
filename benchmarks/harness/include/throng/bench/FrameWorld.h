#pragma once
// What the frame-level benchmarks share: the town world built from a
// scene scaled to an actor count, its impostors as throng-town bakes them, the two cameras, and the
// digest that proves every method of a tick saw one state.

#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "throng/render/ImpostorSet.h"
#include "throng/scenegraph/Image.h"
#include "throng/sim/Simulation.h"

namespace throng::bench {

/// The world of scene file `scene` with its groups scaled to `actors` in all (0: as declared).
std::unique_ptr<sim::Simulation> buildWorld(const std::string& scene, std::int64_t actors);

/// The impostors throng-town draws: every template in use from its main clip, 64 px cells, every
/// other key-frame stored; or as `storage` and `cellSize` say (the atlas-storage comparison).
std::unique_ptr<ImpostorSet> bakeImpostors(const std::shared_ptr<GlContext>& context, const sim::Simulation& world,
                                           AtlasStorage storage = AtlasStorage::HalfKeyframes, int cellSize = 64,
                                           std::size_t drawProxyVertices = ImpostorBakeOptions{}.drawProxyVertices);

/// The scene's impostor distance and hysteresis in metres (40 m when it declares none).
std::pair<double, double> impostorDistance(const sim::Simulation& world);

/// Time on the scene's camera path of a named camera: "street" (eye 2.75 m up) or "overview".
double cameraTime(const std::string& name);

/// FNV-1a over every actor's Reference Point: the simulation state a processor sees.
std::uint64_t stateDigest(const Crowd& crowd);

/// Adds the image error of `frame` against `reference` (same size) to the sums the whole-frame
/// benchmarks report: PSNR in dB (identical frames count as 99), SSIM, and the share of pixels off
/// by more than 8/255.
void addFrameError(const Image& frame, const Image& reference, double& psnr, double& ssim, double& off8);

/// Prints "<program>: <why>" and exits with status 1.
[[noreturn]] void fail(const char* program, const std::string& why);

}  // namespace throng::bench
