#pragma once
// A procedural bird for flocks flying over the town (the seed's actors fly in the sky of Performer
// Town): a body, a head, two wings with a flapping DOF each, a tail. Level 0 shows everything;
// beyond `near` the wings and tail merge into the body's silhouette (their nodes deactivated); beyond
// `far` nothing is drawn. Its clip "flap" beats the wings.

#include <memory>

#include "throng/actors/ActorTemplate.h"

namespace throng {

/// Distances of the bird's levels of detail.
struct ProceduralBirdLods {
    double near = 40.0;   ///< separate wings and tail until here
    double far = 400.0;   ///< one simple body until here
};

/// Builds the bird template (wingspan about 1.2 m).
std::shared_ptr<const ActorTemplate> makeProceduralBird(const ProceduralBirdLods& lods = {});

}  // namespace throng
