#pragma once
// The Skeleton Root's transform relative to the Reference Point (seed 002 Fig. 1). A template over
// its scalar only so that tests can sample clips on an operation-counting type.

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace throng {

/// Where the skeleton hangs relative to the actor's Reference Point, over scalar `S`.
template <class S>
struct BasicRootPose {
    glm::vec<3, S, glm::defaultp> translation{S(0)};                 ///< metres, in the Reference Point frame
    glm::qua<S, glm::defaultp> orientation{S(1), S(0), S(0), S(0)};  ///< unit quaternion
};

/// Where the skeleton hangs relative to the actor's Reference Point (float).
using RootPose = BasicRootPose<float>;

}  // namespace throng
