#pragma once
// Whether the ranks of a throng-town run would build and step the same world: each reads its own
// scene file and command line (on two hosts, two copies), and a rank whose scene, --actors, --seed,
// --frames, --pose-on-ranks, --looks or --faces differ from rank 0's would step other walkers, or stop at another frame, without
// any exchange noticing. Rank 0 sends its WorldKey before anything is built; a rank that differs
// names what differs and stops the run.

#include <cstdint>
#include <optional>
#include <string>

#include "TownOptions.h"

namespace throng::town {

/// What every rank's world depends on, as a flat record that travels between the ranks.
struct WorldKey {
    std::uint64_t sceneHash = 0;  ///< hash of the scene file's bytes
    std::uint64_t sceneBytes = 0; ///< its size
    std::int64_t actors = -1;     ///< --actors, or -1 when not given
    std::uint64_t seed = 0;       ///< --seed, when given
    std::int64_t frames = 0;      ///< --frames: how many steps every rank takes
    std::uint8_t seedGiven = 0;   ///< 1 when --seed was given
    std::uint8_t poseOnRanks = 0; ///< --pose-on-ranks: every rank poses its walkers (and exchanges more)
    std::uint8_t looks = 0;       ///< --looks: what a posing rank's walkers wear
    std::uint8_t faces = 0;       ///< --faces: whether a posing rank's walkers have faces
    std::uint8_t padding[4] = {}; ///< zero, so that equal keys have equal bytes
};

/// The key of the run `o` describes (the scene file read whole). Throws std::runtime_error if the
/// scene file cannot be read.
WorldKey worldKey(const TownOptions& o);

/// What differs between this rank's key `mine` and rank 0's `root`, in words naming the scene file
/// `scene` and the options, or nothing when they agree.
std::optional<std::string> disagreement(const WorldKey& mine, const WorldKey& root, const std::string& scene);

}  // namespace throng::town
