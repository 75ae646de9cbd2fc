#pragma once
// Waiting on rank 0 while it builds the world and bakes impostors, which takes longer than any
// exchange of a running frame may.

#include <algorithm>
#include <chrono>

#include "throng/sim/Ranks.h"

namespace throng::town {

/// Runs `wait` with the ranks' timeout raised to at least 30 minutes, then restores it.
template <class Wait>
auto waitLong(sim::Ranks& ranks, Wait&& wait) {
    const auto timeout = ranks.timeout();
    ranks.setTimeout(std::max<std::chrono::milliseconds>(timeout, std::chrono::minutes(30)));
    auto result = wait();
    ranks.setTimeout(timeout);
    return result;
}

}  // namespace throng::town
