#pragma once
// Blending two poses of the same template: linear for angles, positions and scales, shortest-arc
// normalized blend for orientations.

#include <span>

#include "throng/actors/ActorTemplate.h"

namespace throng::sim {

/// out = (1 - w) a + w b, DOF by DOF, for the nodes flagged in `active` (all when empty).
void blendPoses(const ActorTemplate& tmpl, std::span<const float> a, std::span<const float> b, float w,
                std::span<const std::uint8_t> active, std::span<float> out);

}  // namespace throng::sim
