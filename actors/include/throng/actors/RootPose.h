#pragma once
// The Skeleton Root's transform relative to the Reference Point (seed 002 Fig. 1).

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace throng {

/// Where the skeleton hangs relative to the actor's Reference Point.
struct RootPose {
    glm::vec3 translation{0.0f};         ///< metres, in the Reference Point frame
    glm::quat orientation{1, 0, 0, 0};   ///< unit quaternion
};

}  // namespace throng
