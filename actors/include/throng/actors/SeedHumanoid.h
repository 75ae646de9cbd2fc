#pragma once
// A procedural humanoid like the seed's (seed 002 §7.1, Fig. 5 and 8): 13 articulation points, 19
// DOFs, 5 geometric levels of detail of rigid segments, with skeletal LOD coordinated with them.
// Level 0 shows every segment and the eyes; level 1 drops the eyes; level 2 merges head into torso
// (neck and head deactivated); level 3 shows whole limbs (elbows and knees deactivated); level 4 is
// one piece at the actor level, with no Skeleton node processed (the seed's "LOD formed by none").
// Clips: "walk" (2 s key-framing table) and "pirouette" (the Skeleton Root circles the Reference
// Point, as in the seed's Fig. 2).

#include <memory>

#include "throng/actors/ActorTemplate.h"

namespace throng {

/// Distances (metres) at which the humanoid's geometric levels end.
struct SeedHumanoidLods {
    double eyes = 10.0;       ///< level 0 ends: eyes deactivated
    double head = 30.0;       ///< level 1 ends: head and neck deactivated
    double forearms = 80.0;   ///< level 2 ends: elbows and knees deactivated
    double limbs = 200.0;     ///< level 3 ends: every Skeleton node deactivated
    double figure = 800.0;    ///< level 4 (actor-level piece) ends
};

/// Builds the humanoid template.
std::shared_ptr<const ActorTemplate> makeSeedHumanoid(const SeedHumanoidLods& lods = {});

}  // namespace throng
