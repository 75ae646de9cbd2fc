#pragma once
// Every variant of an experiment on the identical state: the world steps once per tick, outside
// every variant, then each variant runs on what that step left, and the state each one saw is
// checked to be the same (a digest of every actor's Reference Point).

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "throng/bench/FrameWorld.h"

namespace throng::bench {

/// Runs `run(v)` for each of `variants` variants on the state `crowd` is in now, starting with
/// variant `tick % variants` and wrapping (the variants take turns going first, so none always
/// meets the step's cold caches). After each, checks that the crowd's state digest equals what the
/// first saw; otherwise throws std::runtime_error naming the tick and `name(v)`.
template <class Run, class Name>
void runOnSameState(const Crowd& crowd, std::size_t variants, std::int64_t tick, Run&& run, Name&& name) {
    std::uint64_t digest = 0;
    for (std::size_t i = 0; i < variants; ++i) {
        const std::size_t v = (i + std::size_t(tick)) % variants;
        run(v);
        const std::uint64_t d = stateDigest(crowd);
        if (i == 0) digest = d;
        else if (d != digest) throw std::runtime_error("tick " + std::to_string(tick) + ": '" + std::string(name(v)) + "' saw another state");
    }
}

}  // namespace throng::bench
