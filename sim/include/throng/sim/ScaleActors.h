#pragma once
// Resizing a scene: the same groups in the same proportions, a different total.

#include <cstdint>

#include "throng/sim/SceneDescription.h"

namespace throng::sim {

/// Scales every actor group's count so that the scene holds exactly `total` actors, keeping the
/// groups' proportions (largest remainders get the leftovers). A scene with no actor is unchanged.
void scaleActors(SceneDescription& scene, std::int64_t total);

}  // namespace throng::sim
