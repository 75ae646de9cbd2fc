#pragma once
// What every traversal of one frame knows: the simulation time and where to account operations.

#include <cstdint>

namespace throng {

class OpCounter;

/// Time and accounting of the frame being processed.
struct FrameContext {
    double time = 0.0;            ///< simulation time of the frame, seconds
    double deltaTime = 0.0;       ///< time since the previous frame, seconds
    std::uint64_t frame = 0;      ///< frame number, from 0
    OpCounter* counter = nullptr; ///< FMULT accounting, or null when not counting
};

}  // namespace throng
