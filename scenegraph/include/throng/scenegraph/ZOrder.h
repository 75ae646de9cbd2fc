#pragma once
// Where a point of the ground lies along a Z curve (Morton order): points near each other mostly
// get keys near each other. Crowds number their actors in this order of where they start, so that
// the actors a view sees lie side by side in every per-actor array.

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace throng {

/// The Z-curve key of the ground cell (cells of `cell` metres, on x and z) holding (x, z). Ground
/// farther than 2^30 cells from the origin shares the key of the last cell. `cell` must be positive.
inline std::uint64_t zOrder(double x, double z, double cell) {
    constexpr std::int64_t kBias = std::int64_t(1) << 30;
    const auto spread = [](std::uint64_t v) {  // the low 32 bits of v to the even bits
        v &= 0xffffffffull;
        v = (v | (v << 16)) & 0x0000ffff0000ffffull;
        v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
        v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
        v = (v | (v << 2)) & 0x3333333333333333ull;
        v = (v | (v << 1)) & 0x5555555555555555ull;
        return v;
    };
    const auto index = [&](double v) {
        const double c = std::clamp(std::floor(v / cell), double(-kBias), double(kBias));  // NaN: clamp keeps it, below
        return std::uint64_t(std::isnan(c) ? kBias : std::int64_t(c) + kBias);
    };
    return spread(index(x)) | (spread(index(z)) << 1);
}

}  // namespace throng
