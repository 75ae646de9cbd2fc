#pragma once
// What the fuzzers drive with each input: throng-town's start-up without GL. The world a scene
// describes is built (town, navigation mesh, templates with their LOD levels and skeletal LOD,
// actors), stepped twice and culled once by the actor cascade from the scene's camera. Baking
// impostors is left out: it needs a GL context, too slow to make per input.
//
// The errors a bad input may raise are SceneError (a value at a JSON path) and std::runtime_error
// (what the world found building itself: a navigation mesh that cannot be made, a region over its
// capacity). Anything else escapes and is a finding, as is a crash or a sanitizer report.

#include <cstdint>
#include <stdexcept>
#include <string>

#include "throng/actors/ActorProcessor.h"
#include "throng/sim/SceneDescription.h"
#include "throng/sim/SceneError.h"
#include "throng/sim/Simulation.h"

namespace throng::fuzz {

/// Whether `scene` is small enough to build for every input: at most `actors` actors and a town of at
/// most `blocks` blocks. Larger ones are skipped (their parsing was still fuzzed).
inline bool smallEnough(const sim::SceneDescription& scene, std::int64_t actors = 200, int blocks = 9) {
    std::int64_t total = 0;
    for (const auto& g : scene.actors) total += g.count;
    if (total > actors) return false;
    if (scene.town && scene.town->blocksX * scene.town->blocksZ > blocks) return false;
    if (scene.representation.occlusion && scene.representation.occlusion->width * scene.representation.occlusion->height > 512 * 512) return false;
    return true;
}

/// Builds the world of `scene`, steps it twice and culls it once. Returns whether it got that far
/// (false: a SceneError or std::runtime_error, the documented failures).
inline bool startUp(const sim::SceneDescription& scene) {
    try {
        auto world = sim::Simulation::build(scene);
        ActorProcessor processor(world->crowd());
        for (int i = 0; i < 2; ++i) world->step();
        processor.processFrame(world->root(), world->camera().at(world->now().time, 16.0 / 9.0), world->now().time);
        return true;
    } catch (const sim::SceneError&) {
    } catch (const std::runtime_error&) {
    }
    return false;
}

}  // namespace throng::fuzz
