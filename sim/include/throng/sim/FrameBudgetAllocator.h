#pragma once
// A frame-budget allocator: each frame, picks the rung of a ladder (BudgetLadder.h) to keep
// APP+CULL+DRAW under a budget with the least image error, as Unreal's animation budget allocator
// does for tick rates, but choosing among measured settings. Pure logic on the frame times it is
// given, so it is deterministic and testable with synthetic timings.
//
// It learns online: each rung keeps an exponential average of its measured time over the time the
// ladder file measured for it (a load ratio); the cost of any rung is predicted as its ladder time
// times the load ratio of the rung last measured (the larger of its average and its last frame, so
// a rising load is believed at once). It steps down at once, to the most accurate rung predicted to
// fit under `fitShare` of the budget, when a frame of the current rung goes over the budget or the
// prediction for the current rung does. It steps up only after `upFrames` frames in a row in which
// the rung above fits under `upShare` of the budget (hysteresis), then to the most accurate rung
// predicted to fit there; a rung that goes over soon after being stepped up to needs twice as many
// such frames next time (no oscillation), and that penalty is forgiven after a long stay on it.

#include <cstdint>
#include <vector>

#include "throng/sim/BudgetLadder.h"

namespace throng::sim {

/// How a FrameBudgetAllocator decides.
struct FrameBudgetOptions {
    double budgetMs = 100.0;   ///< APP+CULL+DRAW a frame should stay under (> 0)
    double fitShare = 0.85;    ///< stepping down: to the most accurate rung predicted under this share of the budget
    double stayShare = 0.95;   ///< the current rung is left when its prediction exceeds this share of the budget
    double upShare = 0.75;     ///< stepping up: the rung above must be predicted under this share of the budget...
    int upFrames = 20;         ///< ...in this many frames in a row
    int maxUpFrames = 640;     ///< the most frames a penalised rung waits
    double smoothing = 0.2;    ///< weight of a new frame in a rung's average load ratio (0..1]
    int startRung = -1;        ///< the first frame's rung (-1: the most accurate whose ladder time fits fitShare of the budget)
};

/// The per-frame controller of the settings.
class FrameBudgetAllocator {
public:
    /// An allocator over `ladder` (most accurate first). Throws std::invalid_argument naming the
    /// field at fault: empty ladder, non-positive or non-finite budget or ladder time, shares out
    /// of (0, 1], upFrames < 1, a start rung outside the ladder.
    FrameBudgetAllocator(std::vector<BudgetRung> ladder, const FrameBudgetOptions& options);

    /// The rung for the next frame to be prepared.
    int rung() const { return rung_; }
    /// Records that a frame prepared at rung `frameRung` took `ms` of APP+CULL+DRAW (with a
    /// pipeline the frame measured may be older than the current rung), then decides the rung of
    /// the next frame and returns it. Throws std::invalid_argument for a rung outside the ladder or
    /// a negative or non-finite time.
    int observe(int frameRung, double ms);
    /// The predicted APP+CULL+DRAW of `rung` under the current load (its ladder time before any
    /// frame is measured).
    double predictedMs(int rung) const;
    /// The mean measured time of `rung` (exponential average; 0 if never measured).
    double measuredMs(int rung) const { return rungs_[std::size_t(rung)].averageMs; }
    /// The ladder.
    const std::vector<BudgetRung>& ladder() const { return ladder_; }
    /// The options.
    const FrameBudgetOptions& options() const { return options_; }
    /// Frames observed so far.
    std::int64_t frames() const { return frames_; }
    /// Frames observed so far that exceeded the budget.
    std::int64_t framesOver() const { return over_; }
    /// Rung changes made so far (each step up or down counts once).
    std::int64_t changes() const { return changes_; }

private:
    struct Learned {
        double ratio = 0.0;      // exponential average of measured / ladder time
        double lastRatio = 0.0;  // the last frame's
        double averageMs = 0.0;  // exponential average of the measured time
        bool measured = false;
        int upFrames = 0;        // frames in a row needed to step up to this rung
    };
    double loadRatio() const;
    void moveTo(int rung);

    std::vector<BudgetRung> ladder_;
    FrameBudgetOptions options_;
    std::vector<Learned> rungs_;
    int rung_ = 0;
    int lastMeasured_ = -1;      // the rung of the last frame observed
    int comfortable_ = 0;        // frames in a row the upper rung was predicted to fit
    int steppedUpTo_ = -1;       // the rung last stepped up to, while on probation
    int sinceChange_ = 0;        // frames since the last change
    std::int64_t frames_ = 0, over_ = 0, changes_ = 0;
};

}  // namespace throng::sim
