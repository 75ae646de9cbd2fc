#pragma once
// A town-like spread of actors for benchmarks: humanoids walking circles scattered over a square
// of ground, grouped by city block (one ActorGroup per block), seen by a pedestrian's camera.

#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"

namespace throng::testkit {

/// The scene and its camera.
struct TownSpread {
    std::shared_ptr<Group> root;  ///< one ActorGroup per block
    Camera camera;                ///< eye height 1.7 m at the square's centre, looking along +X
};

/// `count` actors of `tmpl` playing clip `clip`, each walking a circle (3 to 13 m across, 1.2 to
/// 1.6 m/s, at a phase of its own) around a random point of a square of side `extent` centred on
/// the origin; drawn from `rng`, actor by actor.
std::vector<KeyframeBehaviour::Actor> circleWalkers(std::shared_ptr<const ActorTemplate> tmpl, int clip, std::size_t count, double extent,
                                                    std::mt19937_64& rng);

/// Adds `actors` walking seed humanoids, spread over a square of side `extent` metres, to `crowd`.
/// Given `figure`, they are of that template instead, playing its clip "walk" (its first clip when
/// it has none by that name).
TownSpread buildTownSpread(Crowd& crowd, std::size_t actors, double extent = 1000.0, double blockSize = 50.0,
                           std::uint64_t seed = 1, std::shared_ptr<const ActorTemplate> figure = nullptr);

}  // namespace throng::testkit
