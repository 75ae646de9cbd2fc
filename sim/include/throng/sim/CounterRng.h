#pragma once
// Counter-based random numbers: a value is a pure function of (seed, stream, counter), so each actor
// draws from its own stream and results do not depend on update order or thread count.

#include <cstdint>

namespace throng::sim {

/// A random stream identified by a seed and a stream number (for example an actor's id).
class CounterRng {
public:
    /// The stream `stream` of `seed`.
    CounterRng(std::uint64_t seed, std::uint64_t stream) : key_(mix(seed ^ mix(stream + 0x9E3779B97F4A7C15ull))) {}

    /// 64 random bits for `counter`.
    std::uint64_t bits(std::uint64_t counter) const { return mix(key_ + mix(counter)); }
    /// A double in [0, 1) for `counter` (53 random bits).
    double uniform(std::uint64_t counter) const { return static_cast<double>(bits(counter) >> 11) * 0x1.0p-53; }
    /// A double in [lo, hi) for `counter`.
    double uniform(std::uint64_t counter, double lo, double hi) const { return lo + (hi - lo) * uniform(counter); }
    /// The next value of a sequential use: uniform(counter++).
    double next() { return uniform(counter_++); }
    /// An integer in [0, n) for `counter` (n > 0).
    std::uint64_t below(std::uint64_t counter, std::uint64_t n) const { return n ? bits(counter) % n : 0; }

    /// SplitMix64's finaliser: a bijective mixing of 64 bits.
    static constexpr std::uint64_t mix(std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }

private:
    std::uint64_t key_;
    std::uint64_t counter_ = 0;
};

}  // namespace throng::sim
