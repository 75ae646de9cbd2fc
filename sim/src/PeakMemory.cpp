#include "throng/sim/PeakMemory.h"

#include <sys/resource.h>

namespace throng::sim {

std::uint64_t peakResidentBytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0 || usage.ru_maxrss < 0) return 0;
    return std::uint64_t(usage.ru_maxrss) * 1024u;  // Linux counts kibibytes
}

}  // namespace throng::sim
