#include "throng/scenegraph/FramePipeline.h"

#include "throng/scenegraph/Stopwatch.h"

namespace throng {

FramePipeline::FramePipeline(bool overlap) : overlap_(overlap) {
    if (overlap_) worker_ = std::thread([this] { work(); });
}

FramePipeline::~FramePipeline() {
    if (!worker_.joinable()) return;
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_one();
    worker_.join();
}

void FramePipeline::work() {
    std::unique_lock lock(mutex_);
    for (;;) {
        wake_.wait(lock, [this] { return stop_ || job_ != nullptr; });
        if (stop_) return;
        const std::function<void()>* job = job_;
        lock.unlock();
        std::exception_ptr error;
        try {
            (*job)();
        } catch (...) {
            error = std::current_exception();
        }
        lock.lock();
        job_ = nullptr;
        error_ = error;
        busy_ = false;
        done_.notify_one();
    }
}

void FramePipeline::run(const std::function<void()>& prepareNext, const std::function<void()>& drawCurrent) {
    waitMs_ = 0.0;
    if (!overlap_) {
        drawCurrent();
        prepareNext();
        return;
    }
    {
        std::lock_guard lock(mutex_);
        job_ = &prepareNext;
        busy_ = true;
        error_ = nullptr;
    }
    wake_.notify_one();
    std::exception_ptr drawError;
    try {
        drawCurrent();
    } catch (...) {
        drawError = std::current_exception();
    }
    Stopwatch wait;
    std::unique_lock lock(mutex_);
    done_.wait(lock, [this] { return !busy_; });
    waitMs_ = wait.elapsedMs();
    if (error_) std::rethrow_exception(error_);
    if (drawError) std::rethrow_exception(drawError);
}

}  // namespace throng
