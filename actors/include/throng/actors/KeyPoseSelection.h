#pragma once
// Which key-poses a fixed-size cache should hold this frame (seed 004). Each actor served by the
// cache needs one key-pose (intermittent mode) or the two that enclose its clip time (interpolative
// mode); actors needing the same poses form one demand. Choosing the poses that serve the most
// actors is the set-union knapsack problem of §4.1 (NP-hard): selectKeyPosesGreedy is the
// real-time heuristic of §4.2, KeyPoseExactSelection the optimum it is measured against.

#include <cstdint>
#include <span>
#include <vector>

namespace throng {

/// How many actors need key-poses `a` and `b` this frame (a == b: one pose, intermittent mode).
struct KeyPoseDemand {
    std::uint32_t a = 0;       ///< first key-pose
    std::uint32_t b = 0;       ///< second key-pose (equal to `a` when one pose is enough)
    std::uint32_t actors = 0;  ///< actors needing exactly these poses
};

/// The greedy selection of seed 004 §4.2, generalised to demands of one or two poses: demands in
/// decreasing number of actors (ties: those needing fewer poses not in `resident`, then by pose
/// indices) add their poses while the poses still fit in `capacity`; a demand that does not fit is
/// skipped and the next one tried (the paper's text stops at the first; skipping is never worse).
/// For intermittent demands this is the optimum (sort by count, fill until full). Returns the
/// chosen poses in the order they were added (at most `capacity`). Deterministic.
std::vector<std::uint32_t> selectKeyPosesGreedy(std::span<const KeyPoseDemand> demand, std::uint32_t capacity,
                                                std::span<const std::uint32_t> resident = {});

/// Scratch of the greedy selection, kept by the caller from frame to frame: once it has seen a
/// frame's demands and poses, selecting again allocates nothing.
struct KeyPoseSelectionWorkspace {
    std::vector<std::uint32_t> order;    ///< demands, best first
    std::vector<std::uint8_t> resident;  ///< per pose: held before this selection
    std::vector<std::uint8_t> chosen;    ///< per pose: chosen so far
};

/// selectKeyPosesGreedy writing the chosen poses into `chosen` (emptied first), with its scratch in
/// `workspace`; the same result.
void selectKeyPosesGreedy(std::span<const KeyPoseDemand> demand, std::uint32_t capacity,
                          std::span<const std::uint32_t> resident, KeyPoseSelectionWorkspace& workspace,
                          std::vector<std::uint32_t>& chosen);

/// Actors whose every pose is in `poses`.
std::uint64_t actorsServed(std::span<const KeyPoseDemand> demand, std::span<const std::uint32_t> poses);

}  // namespace throng
