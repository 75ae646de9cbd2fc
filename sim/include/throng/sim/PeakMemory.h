#pragma once
// How much memory this process has held at most: what a rank reports with each step, so that a
// run across ranks says what each process needed, not only rank 0.

#include <cstdint>

namespace throng::sim {

/// The largest resident set this process has had so far, in bytes (getrusage's ru_maxrss); 0 where
/// the system does not say.
std::uint64_t peakResidentBytes();

}  // namespace throng::sim
