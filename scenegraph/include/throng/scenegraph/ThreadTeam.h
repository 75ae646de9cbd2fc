#pragma once
// Data-parallel loops whose results do not depend on the number of threads. [0, n) is cut into
// fixed chunks of `grain` elements (the cut depends on n and grain only, never on timing or on the
// thread count); chunks run on oneTBB's scheduler; whatever a chunk produces is kept per chunk and
// joined in chunk order by the caller, so 1, 2 or N threads give bitwise identical results.
// A ThreadTeam bounds how many threads the loops started inside its run() may use.

#include <cstddef>
#include <memory>

#include "throng/scenegraph/CallableRef.h"

namespace throng {

/// body(chunk, begin, end): one chunk of a loop over [0, n) (referred to, never copied: a loop
/// allocates nothing to call it).
using ChunkBody = CallableRef<void(std::size_t chunk, std::size_t begin, std::size_t end)>;

/// Number of chunks of `grain` elements covering [0, n) (the last may be shorter).
inline std::size_t chunkCount(std::size_t n, std::size_t grain) { return grain == 0 ? 0 : (n + grain - 1) / grain; }

/// Calls body for every chunk of [0, n), in parallel on the threads of the enclosing
/// ThreadTeam::run() (all of the machine's outside one). Returns when every chunk is done; the
/// first exception a chunk throws is rethrown here. Throws std::invalid_argument if `grain` is 0.
void forEachChunk(std::size_t n, std::size_t grain, ChunkBody body);

/// How many threads may run the chunks of a forEachChunk started here (the enclosing team's size, or
/// the machine's outside one): the number of per-thread scratch slots a loop body may index.
std::size_t workerSlots();
/// The calling thread's index among workerSlots() (each thread running chunks has its own), for
/// scratch a chunk must not share with one running at the same time, such as a navigation query.
std::size_t workerIndex();

/// A bounded set of threads (a oneTBB task arena).
class ThreadTeam {
public:
    /// A team of `threads` threads, the caller's included. Throws std::invalid_argument if 0.
    /// More threads than the machine has are allowed (they share its cores).
    explicit ThreadTeam(unsigned threads);
    ~ThreadTeam();
    ThreadTeam(const ThreadTeam&) = delete;
    ThreadTeam& operator=(const ThreadTeam&) = delete;

    /// Number of threads.
    unsigned threads() const { return threads_; }
    /// Runs `work` on the calling thread with the team's threads serving every forEachChunk inside.
    void run(CallableRef<void()> work);

private:
    struct Impl;
    unsigned threads_;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
