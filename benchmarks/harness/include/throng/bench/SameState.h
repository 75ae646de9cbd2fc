#pragma once
// Every variant of an experiment on the identical state: the world steps once per tick, outside
// every variant, then each variant runs on what that step left, and the state each one saw is
// checked to be the same (a digest of every actor's Reference Point).

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "throng/bench/FrameWorld.h"

namespace throng::bench {

/// Runs `run(v)` for each of `variants` variants, starting with variant `tick % variants` and
/// wrapping (the variants take turns going first, so none always meets the step's cold caches).
/// After each, `digest(v)` gives the state digest that variant saw; all must equal the first's,
/// otherwise throws std::runtime_error naming the tick and `name(v)`. For variants on worlds of
/// their own that must step alike.
template <class Run, class Digest, class Name>
void runOnSameStates(std::size_t variants, std::int64_t tick, Run&& run, Digest&& digest, Name&& name) {
    std::uint64_t first = 0;
    for (std::size_t i = 0; i < variants; ++i) {
        const std::size_t v = (i + std::size_t(tick)) % variants;
        run(v);
        const std::uint64_t d = digest(v);
        if (i == 0) first = d;
        else if (d != first) throw std::runtime_error("tick " + std::to_string(tick) + ": '" + std::string(name(v)) + "' saw another state");
    }
}

/// runOnSameStates for variants that all run on `crowd` (one world): the digest is the crowd's
/// state after each variant ran.
template <class Run, class Name>
void runOnSameState(const Crowd& crowd, std::size_t variants, std::int64_t tick, Run&& run, Name&& name) {
    runOnSameStates(variants, tick, std::forward<Run>(run), [&](std::size_t) { return stateDigest(crowd); }, std::forward<Name>(name));
}

}  // namespace throng::bench
