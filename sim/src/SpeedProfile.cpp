#include "throng/sim/SpeedProfile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace throng::sim {
namespace {

// RiMEA guideline, Test 7 (walking speeds on the level after Weidmann 1993), m/s.
constexpr std::array kProfiles{
    SpeedProfile{"rimea-under-30", "people under 30", 0.58, 1.61},
    SpeedProfile{"rimea-30-to-50", "people from 30 to 50", 1.41, 1.54},
    SpeedProfile{"rimea-over-50", "people over 50", 0.68, 1.41},
    SpeedProfile{"rimea-impaired", "people of reduced mobility", 0.46, 0.76},
};

double normalCdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

}  // namespace

double SpeedProfile::draw(const CounterRng& rng, std::uint64_t counter) const {
    // Box-Muller pairs until one falls inside the range (the range holds 95 % of the normal, so
    // one try in 20 is redrawn); the counters lie apart from the stream's other uses.
    const std::uint64_t base = (counter << 7) + (std::uint64_t(3) << 60);
    for (std::uint64_t k = 0; k < 32; ++k) {
        const double u1 = 1.0 - rng.uniform(base + 2 * k), u2 = rng.uniform(base + 2 * k + 1);
        const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
        const double v = mean() + deviation() * z;
        if (v >= lo && v <= hi) return v;
    }
    return mean();  // 32 misses in a row: about one chance in 10^41
}

double SpeedProfile::cumulative(double speed) const {
    if (speed <= lo) return 0.0;
    if (speed >= hi) return 1.0;
    const double a = normalCdf(-2.0), b = normalCdf(2.0);
    return (normalCdf((speed - mean()) / deviation()) - a) / (b - a);
}

std::span<const SpeedProfile> speedProfiles() { return kProfiles; }

const SpeedProfile* findSpeedProfile(std::string_view name) {
    const auto it = std::find_if(kProfiles.begin(), kProfiles.end(), [&](const SpeedProfile& p) { return p.name == name; });
    return it == kProfiles.end() ? nullptr : &*it;
}

}  // namespace throng::sim
