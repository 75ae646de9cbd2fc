#pragma once
// GPU time of a frame's DRAW passes, measured with GL timer queries (GL_TIME_ELAPSED, core in
// OpenGL 3.3) apart from the CPU time spent preparing and submitting them. Queries go round three
// sets, and results are read only once GL says they are available, so timing never stalls the
// pipeline: a frame's times arrive when the GPU has finished it (at once headless, where a frame
// ends with glFinish; a frame or two later in a window).

#include <array>
#include <cstdint>

namespace throng {

class GlContext;

/// The passes of a crowd frame's DRAW that are timed on the GPU.
enum class GpuPass { Town, Meshes, Impostors, Finish };

/// GPU milliseconds of each pass of one frame.
struct GpuPassTimes {
    std::array<double, 4> ms{};   ///< indexed by GpuPass
    std::int64_t frame = -1;      ///< the frame (count of beginFrame calls from 0) they were measured on; -1: none yet
    /// Their sum: the frame's DRAW on the GPU.
    double totalMs() const { return ms[0] + ms[1] + ms[2] + ms[3]; }
};

/// Timer queries around each DRAW pass of successive frames.
class GpuPassTimer {
public:
    /// Queries made in `context` (current on the calling thread whenever the timer is used).
    explicit GpuPassTimer(GlContext& context);
    ~GpuPassTimer();
    GpuPassTimer(const GpuPassTimer&) = delete;
    GpuPassTimer& operator=(const GpuPassTimer&) = delete;

    /// Starts a frame: its queries take the set of the frame three back, whose results (if it has
    /// not given them yet) are read first, waiting for none.
    void beginFrame();
    /// Times `pass` from here to end(); one pass at a time, each at most once a frame.
    void begin(GpuPass pass);
    /// Ends the pass begun.
    void end();
    /// Reads every finished frame's results without waiting; the newest become latest().
    void collect();
    /// The newest frame whose passes all finished on the GPU.
    const GpuPassTimes& latest() const { return latest_; }
    /// The current frame's number (beginFrame calls so far, less one).
    std::int64_t frame() const { return frame_; }

private:
    static constexpr int kSets = 3;
    struct Set {
        std::array<unsigned, 4> queries{};
        std::array<bool, 4> used{};
        std::int64_t frame = -1;  // -1: holds no pending results
    };
    void read(Set& set);

    GlContext& context_;
    std::array<Set, kSets> sets_{};
    std::int64_t frame_ = -1;
    int active_ = -1;  // the pass begun, or -1
    GpuPassTimes latest_;
};

}  // namespace throng
