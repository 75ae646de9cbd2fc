#include "throng/scenegraph/ThreadTeam.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

namespace throng {

void forEachChunk(std::size_t n, std::size_t grain, ChunkBody body) {
    if (grain == 0) throw std::invalid_argument("forEachChunk: argument 'grain' must be at least 1");
    const std::size_t chunks = chunkCount(n, grain);
    if (chunks == 0) return;
    if (chunks == 1 || oneapi::tbb::this_task_arena::max_concurrency() == 1) {
        for (std::size_t c = 0; c < chunks; ++c) body(c, c * grain, std::min(n, (c + 1) * grain));
        return;
    }
    // One task per chunk: a simple partitioner never merges ranges, so the cut stays the fixed one.
    oneapi::tbb::parallel_for(
        oneapi::tbb::blocked_range<std::size_t>(0, chunks, 1),
        [&](const oneapi::tbb::blocked_range<std::size_t>& r) {
            for (std::size_t c = r.begin(); c != r.end(); ++c) body(c, c * grain, std::min(n, (c + 1) * grain));
        },
        oneapi::tbb::simple_partitioner());
}

std::size_t workerSlots() { return static_cast<std::size_t>(std::max(1, oneapi::tbb::this_task_arena::max_concurrency())); }

std::size_t workerIndex() {
    const int index = oneapi::tbb::this_task_arena::current_thread_index();
    return index < 0 ? 0 : static_cast<std::size_t>(index);
}

struct ThreadTeam::Impl {
    // Lets the scheduler run more threads than the machine has cores when a team asks for them.
    std::optional<oneapi::tbb::global_control> allowance;
    oneapi::tbb::task_arena arena;
    explicit Impl(unsigned threads) : arena(static_cast<int>(threads)) {
        if (threads > std::thread::hardware_concurrency())
            allowance.emplace(oneapi::tbb::global_control::max_allowed_parallelism, threads);
    }
};

ThreadTeam::ThreadTeam(unsigned threads) : threads_(threads) {
    if (threads == 0) throw std::invalid_argument("ThreadTeam: argument 'threads' must be at least 1");
    impl_ = std::make_unique<Impl>(threads);
}

ThreadTeam::~ThreadTeam() = default;

void ThreadTeam::run(CallableRef<void()> work) { impl_->arena.execute([work] { work(); }); }

}  // namespace throng
