#pragma once
// Whether a crowd fits in the memory this process may use, decided before anything is allocated:
// a run too large for the machine stops with a message naming the limit instead of being killed
// by the kernel half-way through building.

#include <cstdint>
#include <optional>
#include <string>

#include "throng/sim/SceneDescription.h"

namespace throng::town {

/// Peak resident memory a run of `scene` needs, estimated from measured runs of the default scene
/// (`throng-town --actors N --frames 2`, 10k to 1M actors): 450 MiB plus 5 KiB per actor.
std::uint64_t estimatedPeakBytes(const sim::SceneDescription& scene);

/// The memory this process may use and what sets it.
struct MemoryLimit {
    std::uint64_t bytes = 0;  ///< bytes it may still use
    std::string what;         ///< "MemAvailable", "the cgroup's memory.max", "the address-space limit (ulimit -v)"
};

/// The least of: the kernel's MemAvailable, the cgroup's memory.max less its usage, and
/// RLIMIT_AS less the address space already mapped. A source that cannot be read is left out.
MemoryLimit availableMemory();

/// The problem, if `scene` needs more than `limit`: one line naming both and the crowd that fits.
std::optional<std::string> memoryProblem(const sim::SceneDescription& scene, const MemoryLimit& limit);

}  // namespace throng::town
