#pragma once
// Performer's multiprocess mode for two stages: while DRAW renders frame N on the calling thread
// (the one that owns the GL context), the next frame's step, APP and CULL run on a worker thread.
// DRAW reads only the double-buffered data frame N left (its own draw list, palettes and camera),
// so the overlap changes when work happens, never what is drawn. With overlap off, the same calls
// run one after the other on the calling thread.

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace throng {

/// Runs "prepare the next frame" beside "draw this frame".
class FramePipeline {
public:
    /// A pipeline that overlaps the two stages when `overlap` is true.
    explicit FramePipeline(bool overlap);
    ~FramePipeline();
    FramePipeline(const FramePipeline&) = delete;
    FramePipeline& operator=(const FramePipeline&) = delete;

    /// Whether the stages overlap.
    bool overlapping() const { return overlap_; }
    /// Runs `prepareNext` (on the worker when overlapping) and `drawCurrent` (on the calling thread),
    /// and returns when both are done. An exception from either is rethrown here (prepareNext's first).
    void run(const std::function<void()>& prepareNext, const std::function<void()>& drawCurrent);
    /// Milliseconds the calling thread waited for prepareNext after drawing, in the last run().
    double lastWaitMs() const { return waitMs_; }

private:
    void work();

    bool overlap_;
    std::thread worker_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const std::function<void()>* job_ = nullptr;
    bool busy_ = false, stop_ = false;
    std::exception_ptr error_;
    double waitMs_ = 0.0;
};

}  // namespace throng
