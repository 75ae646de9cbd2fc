#pragma once
// Internal to sim: what Locomotion knows of one walker while it moves. The region stepper moves it
// (DetourCrowd's position and velocity, destinations), the walker behaviour turns it into a gait
// (heading, speed, walk phase, run weight) and poses it, and the rank exchange copies it between
// processes. The region owning each walker is kept apart, one number per walker, so that a frame
// reads it without the rest (occlusion's cells). The records the regions and ranks exchange are here too.

#include <cstdint>

#include <glm/vec3.hpp>

#include "throng/scenegraph/BoundingSphere.h"

namespace throng::sim::locomotion {

/// One walker's moving state.
struct WalkerState {
    glm::vec3 position{0.0f};   ///< where it stands
    float heading = 0.0f;       ///< radians about +Y; local +Z faces along it
    float speed = 0.0f;         ///< m/s, after the last step
    double phase = 0.0;         ///< walk cycle, in cycles (the run clip follows in step)
    float runWeight = 0.0f;     ///< how far the run clip is blended in
    std::uint64_t trips = 0;    ///< destinations drawn so far
    glm::vec3 target{0.0f};     ///< where it is walking to
    glm::vec3 velocity{0.0f};   ///< DetourCrowd's, after the last step
    int agent = -1;             ///< index in its region's crowd
    BoundingSphere extent;      ///< where its Skeleton Root may go, Reference Point frame
    double blendMargin = 0.0;   ///< how far walk-run blends reach beyond the Sklsroot Bsphere
    std::uint8_t carried = 0;   ///< what the process posing it keeps with it (Locomotion::carried)
};

/// An agent as a neighbouring region sees it for avoidance during one step.
struct GhostRecord {
    std::uint32_t slot = 0;        ///< the actor
    std::uint32_t region = 0;      ///< the region that sees it
    float position[3] = {};        ///< at the start of the step
    float velocity[3] = {};        ///< at the start of the step
};

/// An agent leaving its region at the end of a step, with everything it walks on with (the
/// region entered may belong to another rank, which knows nothing else of it).
struct HandoverRecord {
    std::uint32_t slot = 0;        ///< the actor
    std::uint32_t from = 0;        ///< region left
    std::uint32_t to = 0;          ///< region entered
    float position[3] = {};        ///< where it is
    float velocity[3] = {};        ///< how it moves
    float target[3] = {};          ///< where it is walking to
    float heading = 0.0f;          ///< radians about +Y
    float speed = 0.0f;            ///< m/s, after the previous step
    float runWeight = 0.0f;        ///< how far the run clip is blended in
    std::uint32_t carried = 0;     ///< what the process posing it keeps with it (in what was padding)
    double phase = 0.0;            ///< walk cycle, in cycles
    std::uint64_t trips = 0;       ///< destinations drawn so far
};

/// What rank 0 draws a walker from, sent by the rank stepping it after each step.
struct WalkerRecord {
    std::uint32_t slot = 0;        ///< the actor
    std::uint32_t region = 0;      ///< the region owning it
    float position[3] = {};        ///< where it stands
    float heading = 0.0f;          ///< radians about +Y
    float speed = 0.0f;            ///< m/s
    float runWeight = 0.0f;        ///< how far the run clip is blended in
    double phase = 0.0;            ///< walk cycle, in cycles
};

}  // namespace throng::sim::locomotion
