#pragma once
// Resizing a scene: the same groups in the same proportions, a different total, and a town grown
// to hold them at the scene's own density.

#include <cstdint>

#include "throng/sim/SceneDescription.h"

namespace throng::sim {

/// The most city blocks one town holds: its navigation mesh is one Recast tile, whose polygon mesh
/// numbers vertices with 16 bits (the default scene's tiles: 24 x 24 blocks build, 40 x 40 do not).
inline constexpr std::int64_t kMaxTownBlocks = 24 * 24;

/// Scales every actor group's count so that the scene holds exactly `total` actors, keeping the
/// groups' proportions (largest remainders get the leftovers). A scene with no actor is unchanged.
/// A town grows with the crowd (never shrinks) so that actors per block stay as the scene declares
/// them, and the groups' areas grow with it. Throws std::invalid_argument, saying why and which
/// count the scene would hold, if the grown town would exceed kMaxTownBlocks.
void scaleActors(SceneDescription& scene, std::int64_t total);

}  // namespace throng::sim
