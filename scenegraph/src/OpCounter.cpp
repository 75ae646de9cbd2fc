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

}  // namespace throng
