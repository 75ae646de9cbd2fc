// Memory a crowd needs against what the process may use (MemoryNeed.h).

#include "MemoryNeed.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace throng::town {
namespace {

// Fitted above the peaks of the default scene's runs (10k: 436 MiB, 100k: 895, 300k: 1,767, 1M:
// 4,660): town, templates, GL and libraries, then each actor.
constexpr std::uint64_t kFixedBytes = 450ull << 20;
constexpr std::uint64_t kBytesPerActor = 5ull << 10;

std::int64_t totalActors(const sim::SceneDescription& scene) {
    std::int64_t n = 0;
    for (const auto& g : scene.actors) n += g.count;
    return n;
}

std::string gib(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1ull << 30));
    return text;
}

// A number from a file that holds one ("max" or unreadable: none).
std::optional<std::uint64_t> numberIn(const char* path) {
    std::ifstream in(path);
    std::uint64_t v = 0;
    if (in >> v) return v;
    return std::nullopt;
}

}  // namespace

std::uint64_t estimatedPeakBytes(const sim::SceneDescription& scene) {
    return kFixedBytes + kBytesPerActor * std::uint64_t(std::max<std::int64_t>(totalActors(scene), 0));
}

MemoryLimit availableMemory() {
    MemoryLimit limit{~std::uint64_t(0), "no limit known"};
    const auto consider = [&](std::uint64_t bytes, const char* what) {
        if (bytes < limit.bytes) limit = {bytes, what};
    };
    std::ifstream meminfo("/proc/meminfo");
    for (std::string line; std::getline(meminfo, line);)
        if (line.rfind("MemAvailable:", 0) == 0) {
            std::istringstream s(line.substr(13));
            std::uint64_t kib = 0;
            if (s >> kib) consider(kib << 10, "MemAvailable");
        }
    if (const auto max = numberIn("/sys/fs/cgroup/memory.max")) {
        const std::uint64_t used = numberIn("/sys/fs/cgroup/memory.current").value_or(0);
        consider(*max > used ? *max - used : 0, "the cgroup's memory.max");
    }
    rlimit as{};
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
        std::uint64_t mapped = 0;  // pages of address space in use (/proc/self/statm's first field)
        std::ifstream statm("/proc/self/statm");
        statm >> mapped;
        mapped *= std::uint64_t(sysconf(_SC_PAGESIZE));
        consider(as.rlim_cur > mapped ? as.rlim_cur - mapped : 0, "the address-space limit (ulimit -v)");
    }
    return limit;
}

std::optional<std::string> memoryProblem(const sim::SceneDescription& scene, const MemoryLimit& limit) {
    const std::uint64_t need = estimatedPeakBytes(scene);
    if (need <= limit.bytes) return std::nullopt;
    const std::uint64_t fit = limit.bytes > kFixedBytes ? (limit.bytes - kFixedBytes) / kBytesPerActor : 0;
    return std::to_string(totalActors(scene)) + " actors need about " + gib(need) + " of memory (450 MiB and 5 KiB per actor, as measured), but " +
           limit.what + " leaves " + gib(limit.bytes) + ": about " + std::to_string(fit) + " actors fit (--actors)";
}

}  // namespace throng::town
