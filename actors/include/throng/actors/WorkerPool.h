#pragma once
// A fixed set of worker threads for data-parallel loops over actors. A loop is split into one
// contiguous range per thread; every element is computed the same way whichever thread runs it,
// so results are bitwise identical with 1 or N threads.

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace throng {

/// Persistent workers running `parallelFor` loops.
class WorkerPool {
public:
    /// A pool of `threads` threads in all (the caller's included); 1 runs everything inline.
    /// Throws std::invalid_argument if `threads` is 0.
    explicit WorkerPool(unsigned threads);
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    /// Number of threads (the caller's included).
    unsigned threads() const { return static_cast<unsigned>(workers_.size()) + 1; }
    /// Calls body(begin, end) on disjoint ranges covering [0, n), one per thread, and returns when
    /// all are done. The first exception thrown by a range is rethrown here.
    void parallelFor(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body);

private:
    void work(unsigned index);

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable start_, done_;
    const std::function<void(std::size_t, std::size_t)>* body_ = nullptr;
    std::size_t n_ = 0;
    std::size_t generation_ = 0;
    unsigned pending_ = 0;
    bool stop_ = false;
    std::exception_ptr error_;
};

}  // namespace throng
