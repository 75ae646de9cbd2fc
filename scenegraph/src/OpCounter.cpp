#include "throng/scenegraph/OpCounter.h"

namespace throng {

std::uint64_t OpCounter::totalFmult() const {
    std::uint64_t total = 0;
    for (const OpTally& t : tallies_) total += t.fmult();
    return total;
}

void OpCounter::reset() {
    operations_.fill(0);
    tallies_.fill(OpTally{});
}

void OpCounter::add(const OpCounter& other) {
    for (std::size_t i = 0; i < kOpCategoryCount; ++i) {
        operations_[i] += other.operations_[i];
        tallies_[i] += other.tallies_[i];
    }
}

}  // namespace throng
