#pragma once
// Per-frame accounting of the scenegraph's work by the categories of Table 1 (NO_01 ... NO_05):
// how many operations of each kind were done (NO_xx) and what they cost in FMULT.

#include <array>
#include <cstdint>

#include "throng/scenegraph/OpCategory.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

/// Accumulates operation counts and FMULT costs per category. Disabled by default; when disabled,
/// tally() returns null so that counting sites skip their work.
class OpCounter {
public:
    /// Switches counting on or off at run time.
    void setEnabled(bool enabled) { enabled_ = enabled; }
    /// Whether counting is on.
    bool enabled() const { return enabled_; }
    /// Whether counting was compiled in (THRONG_OP_COUNTING).
    static constexpr bool compiledIn() { return THRONG_OP_COUNTING != 0; }

    /// The tally to pass to counted primitives for `category`, or null when counting is off.
    OpTally* tally(OpCategory category) { return enabled_ ? &tallies_[index(category)] : nullptr; }
    /// Records `n` operations of `category` (the NO_xx count); their cost goes through tally().
    void countOperations(OpCategory category, std::uint64_t n = 1) {
        if constexpr (compiledIn()) {
            if (enabled_) operations_[index(category)] += n;
        }
    }

    /// Number of operations recorded for `category` (NO_xx).
    std::uint64_t operations(OpCategory category) const { return operations_[index(category)]; }
    /// Elementary operations recorded for `category`.
    const OpTally& ops(OpCategory category) const { return tallies_[index(category)]; }
    /// FMULT cost recorded for `category`.
    std::uint64_t fmult(OpCategory category) const { return tallies_[index(category)].fmult(); }
    /// FMULT cost of all categories.
    std::uint64_t totalFmult() const;
    /// Clears all counts (keeps the enabled state).
    void reset();
    /// Adds the counts of `other` (a chunk's or a thread's counter) to these.
    void add(const OpCounter& other);

private:
    static constexpr std::size_t index(OpCategory c) { return static_cast<std::size_t>(c); }
    bool enabled_ = false;
    std::array<std::uint64_t, kOpCategoryCount> operations_{};
    std::array<OpTally, kOpCategoryCount> tallies_{};
};

/// The tally to pass to counted primitives for `category`, or null when `counter` is null or off.
inline OpTally* tallyFor(OpCounter* counter, OpCategory category) {
    return counter ? counter->tally(category) : nullptr;
}
/// Records `n` operations of `category` when `counter` is non-null.
inline void countOperations(OpCounter* counter, OpCategory category, std::uint64_t n = 1) {
    if (counter) counter->countOperations(category, n);
}

}  // namespace throng
