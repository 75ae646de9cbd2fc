#pragma once
// A town-like spread of actors for benchmarks: humanoids walking circles scattered over a square
// of ground, grouped by city block (one ActorGroup per block), seen by a pedestrian's camera.

#include <cstdint>
#include <memory>

#include "throng/actors/Crowd.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"

namespace throng::testkit {

/// The scene and its camera.
struct TownSpread {
    std::shared_ptr<Group> root;  ///< one ActorGroup per block
    Camera camera;                ///< eye height 1.7 m at the square's centre, looking along +X
};

/// Adds `actors` walking seed humanoids, spread over a square of side `extent` metres, to `crowd`.
/// Given `figure`, they are of that template instead, playing its clip "walk" (its first clip when
/// it has none by that name).
TownSpread buildTownSpread(Crowd& crowd, std::size_t actors, double extent = 1000.0, double blockSize = 50.0,
                           std::uint64_t seed = 1, std::shared_ptr<const ActorTemplate> figure = nullptr);

}  // namespace throng::testkit
