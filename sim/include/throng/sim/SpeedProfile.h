#pragma once
// Free walking speeds of measured people on the level, per population, as the RiMEA guideline
// tabulates them after Weidmann (1993): the range each population walks at. A walker of such a
// group is given a free speed drawn from a normal distribution centred in the range, with a
// quarter of the range as its deviation, cut to the range (a truncated normal): the distribution a
// validation test checks the walkers' measured speeds against.

#include <cstdint>
#include <span>
#include <string_view>

#include "throng/sim/CounterRng.h"

namespace throng::sim {

/// One population's free walking speeds.
struct SpeedProfile {
    std::string_view name;  ///< as a scene names it ("rimea-under-30", ...)
    std::string_view who;   ///< the population, in words
    double lo = 0.0;        ///< slowest free speed, m/s
    double hi = 0.0;        ///< fastest free speed, m/s

    /// The centre of the range, m/s.
    double mean() const { return 0.5 * (lo + hi); }
    /// The deviation of the normal before it is cut: a quarter of the range, m/s.
    double deviation() const { return 0.25 * (hi - lo); }
    /// A speed for `counter` of `rng`, inside [lo, hi] (a pure function of both).
    double draw(const CounterRng& rng, std::uint64_t counter) const;
    /// The share of draws at or below `speed` (the truncated normal's distribution function).
    double cumulative(double speed) const;
};

/// Every population, in the guideline's order.
std::span<const SpeedProfile> speedProfiles();
/// The population called `name`, or null.
const SpeedProfile* findSpeedProfile(std::string_view name);

}  // namespace throng::sim
