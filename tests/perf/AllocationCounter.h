#pragma once
// Counts the heap allocations of the whole test binary (every thread): the binary replaces the C
// allocation functions, which operator new calls too, with ones that count and then allocate as
// glibc does. Under AddressSanitizer, which owns the allocator, nothing is replaced.

#include <cstdint>

namespace throng::testkit {

/// Whether allocations are counted (false under AddressSanitizer).
bool allocationsCounted();

/// Heap allocations (malloc, calloc, realloc, aligned and memalign variants, operator new) made by
/// any thread since the program started.
std::uint64_t heapAllocations();

/// Minor page faults of the process so far (pages the kernel had to map in for it).
long minorPageFaults();

}  // namespace throng::testkit
