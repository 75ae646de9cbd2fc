#include "throng/actors/WorkerPool.h"

#include <stdexcept>

namespace throng {

WorkerPool::WorkerPool(unsigned threads) {
    if (threads == 0) throw std::invalid_argument("WorkerPool: argument 'threads' must be at least 1");
    for (unsigned i = 1; i < threads; ++i) workers_.emplace_back([this, i] { work(i); });
}

WorkerPool::~WorkerPool() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : workers_) t.join();
}

void WorkerPool::parallelFor(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body) {
    if (workers_.empty() || n < 2) {
        if (n) body(0, n);
        return;
    }
    {
        std::lock_guard lock(mutex_);
        body_ = &body;
        n_ = n;
        pending_ = static_cast<unsigned>(workers_.size());
        error_ = nullptr;
        ++generation_;
    }
    start_.notify_all();
    // The caller takes range 0.
    const std::size_t parts = workers_.size() + 1;
    std::exception_ptr mine;
    try {
        body(0, n / parts);
    } catch (...) {
        mine = std::current_exception();
    }
    std::unique_lock lock(mutex_);
    done_.wait(lock, [this] { return pending_ == 0; });
    body_ = nullptr;
    if (mine) std::rethrow_exception(mine);
    if (error_) std::rethrow_exception(error_);
}

void WorkerPool::work(unsigned index) {
    std::size_t seen = 0;
    for (;;) {
        std::unique_lock lock(mutex_);
        start_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        const auto* body = body_;
        const std::size_t n = n_, parts = workers_.size() + 1;
        lock.unlock();
        try {
            (*body)(n * index / parts, n * (index + 1) / parts);
        } catch (...) {
            std::lock_guard g(mutex_);
            if (!error_) error_ = std::current_exception();
        }
        std::lock_guard g(mutex_);
        if (--pending_ == 0) done_.notify_one();
    }
}

}  // namespace throng
