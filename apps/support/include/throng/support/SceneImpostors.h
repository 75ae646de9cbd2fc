#pragma once
// The impostors a scene's world is drawn with, baked the one way throng-town, throng-vtk and the
// whole-frame benchmarks share: every template in use from its main clip, 64 px cells.

#include <memory>

#include "throng/render/ImpostorBaker.h"

namespace throng {
class GlContext;
class ImpostorSet;
namespace sim {
class Simulation;
}
}  // namespace throng

namespace throng::support {

/// The options every template of `world` is baked with: 64 px cells, the scene's atlas storage.
ImpostorBakeOptions sceneBakeOptions(const sim::Simulation& world);

/// Bakes the impostors of `world`'s templates in `context` (any context: the atlases are CPU
/// images a renderer uploads into its own). With `progress`, a terminal progress bar counts the
/// key-frames. Throws as ImpostorSet does.
std::unique_ptr<ImpostorSet> bakeSceneImpostors(const std::shared_ptr<GlContext>& context, const sim::Simulation& world, bool progress);

}  // namespace throng::support
