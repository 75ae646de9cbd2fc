#pragma once
// Seed 004's Figure 7 as a reusable measurement: how many actors a key-pose cache of each size
// serves when its poses are chosen greedily (§4.2), exactly (§4.1, GLPK), naively (the first n
// key-poses) or at random, over a list of frames of demands. The frames come from random instances
// like the paper's (randomKeyPoseFrames), from a CSV file (readKeyPoseDemandsCsv), or later from
// recorded crowd frames.

#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "throng/actors/KeyPoseSelection.h"

namespace throng::bench {

/// Demands of each frame.
using KeyPoseFrames = std::vector<std::vector<KeyPoseDemand>>;

/// The paper's random instances: each frame `characters` actors over `poses` key-poses; the source
/// pose normal around the middle (standard deviation `sd` poses, rounded and clamped), the
/// destination the next pose (wrapping) with probability `nextPose`, else another normal draw that
/// differs from the source; with `intermittent`, the source alone. Frame f uses seed firstSeed + f
/// (std::mt19937 and Box-Muller: the same frames on every platform).
KeyPoseFrames randomKeyPoseFrames(std::uint32_t frames, std::uint32_t characters, std::uint32_t poses, double sd,
                                  double nextPose, bool intermittent, std::uint32_t firstSeed);

/// Reads demands from CSV text with the header "frame,a,b,actors" (whole numbers, one demand a
/// line; blank lines skipped); frames in increasing frame number, frames without demands omitted.
/// Throws std::runtime_error naming `name` and the line of a malformed entry.
KeyPoseFrames readKeyPoseDemandsCsv(std::istream& in, const std::string& name);

/// The key-poses of an instance: `given` when > 0 (every pose named must be below it), else the
/// largest pose named + 1. Throws std::invalid_argument naming the frame of a pose out of range, or
/// when more than 2^24 key-poses would be needed.
std::uint32_t keyPoseCount(const KeyPoseFrames& frames, std::uint32_t given);

/// What a study measures.
struct KeyPoseStudyOptions {
    std::uint32_t poseCount = 0;      ///< key-poses of the instance (first-n and random-n choose among them); 0: largest named + 1
    double exactTimeLimit = 10.0;     ///< seconds per exact solve
    std::uint32_t randomSeed = 1;     ///< for random-n
    std::uint32_t greedyRepeats = 20; ///< the greedy selection is timed over this many runs
};

/// One cache size, averaged over the frames.
struct KeyPoseStudyRow {
    std::uint32_t capacity = 0;       ///< key-poses the cache holds
    std::size_t frames = 0;           ///< frames measured
    double actors = 0.0;              ///< mean actors per frame
    double greedy = 0.0;              ///< mean actors served by the greedy selection
    double exact = 0.0;               ///< ... by the exact selection
    double firstN = 0.0;              ///< ... by key-poses 0 .. n-1
    double randomN = 0.0;             ///< ... by n key-poses drawn at random
    double greedyOverExact = 1.0;     ///< sum greedy / sum exact
    double worstGreedyOverExact = 1.0;  ///< smallest per-frame greedy / exact (frames where exact > 0)
    std::size_t greedyBelowExact = 0; ///< frames where the greedy selection serves fewer
    std::size_t exactUnproven = 0;    ///< frames where the exact solve stopped at a limit
    double exactBound = 0.0;          ///< mean proven upper bound (== exact when every frame is proven)
    double greedyMicroseconds = 0.0;  ///< mean time of one greedy selection
    double exactMicrosecondsMean = 0.0;  ///< mean time of one exact selection
    double exactMicrosecondsMax = 0.0;   ///< longest exact selection
};

/// Measures every method for each capacity over `frames`.
std::vector<KeyPoseStudyRow> studyKeyPoseSelection(const KeyPoseFrames& frames, std::span<const std::uint32_t> capacities,
                                                   const KeyPoseStudyOptions& options);

/// Writes the rows as CSV (a header line, one line per capacity).
void writeKeyPoseStudyCsv(std::ostream& out, std::span<const KeyPoseStudyRow> rows);

}  // namespace throng::bench
