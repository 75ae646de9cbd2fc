#pragma once
// Resizing a scene: the same groups in the same proportions, a different total, and a town grown
// to hold them at the scene's own density.

#include <cstdint>

#include "throng/sim/SceneDescription.h"

namespace throng::sim {

/// The most tiles a town may have, as a scene declares it or grown with its crowd: memory and
/// build time grow with them (the scene graph, the navigation geometry and mesh).
inline constexpr std::int64_t kMaxTownTiles = 300'000;

/// Scales every actor group's count so that the scene holds exactly `total` actors, keeping the
/// groups' proportions (largest remainders get the leftovers). A scene with no actor is unchanged.
/// A town grows with the crowd (never shrinks) so that actors per block stay as the scene declares
/// them, and the groups' areas grow with it. Throws std::invalid_argument, saying why and which
/// count the scene would hold, if the grown town would exceed kMaxTownTiles.
void scaleActors(SceneDescription& scene, std::int64_t total);

}  // namespace throng::sim
