#pragma once
// Counters proving that only the effects a scene declares run: each effect counts when it is
// constructed and each time it is ticked. An undeclared effect shows zero for both.

#include <cstdint>
#include <map>
#include <string>

namespace throng::sim {

/// Construction and tick counts per effect name ("locomotion", "avoidance", "gaze", "idle", "flight").
class EffectCounters {
public:
    /// What one effect did.
    struct Counts {
        std::uint64_t constructed = 0;  ///< instances made
        std::uint64_t ticks = 0;        ///< actor updates (or crowd steps) done
    };
    /// Records that an instance of `effect` was made.
    void constructed(const std::string& effect) { counts_[effect].constructed += 1; }
    /// Records `n` ticks of `effect`.
    void ticked(const std::string& effect, std::uint64_t n = 1) { counts_[effect].ticks += n; }
    /// Counts of `effect` (zero if it never ran).
    Counts of(const std::string& effect) const {
        const auto it = counts_.find(effect);
        return it == counts_.end() ? Counts{} : it->second;
    }
    /// Every effect seen so far.
    const std::map<std::string, Counts>& all() const { return counts_; }

private:
    std::map<std::string, Counts> counts_;
};

}  // namespace throng::sim
