// The frame-budget allocator: learning each rung's load ratio and stepping with hysteresis.

#include "throng/sim/FrameBudgetAllocator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace throng::sim {

namespace {

void requireShare(const char* name, double v) {
    if (!(v > 0.0 && v <= 1.0)) throw std::invalid_argument(std::string("frame budget: ") + name + " must be in (0, 1], not " + std::to_string(v));
}

}  // namespace

FrameBudgetAllocator::FrameBudgetAllocator(std::vector<BudgetRung> ladder, const FrameBudgetOptions& options)
    : ladder_(std::move(ladder)), options_(options) {
    if (ladder_.empty()) throw std::invalid_argument("frame budget: the ladder has no rung");
    if (!(std::isfinite(options_.budgetMs) && options_.budgetMs > 0.0))
        throw std::invalid_argument("frame budget: the budget must be a finite number of ms > 0, not " + std::to_string(options_.budgetMs));
    requireShare("fitShare", options_.fitShare);
    requireShare("stayShare", options_.stayShare);
    requireShare("upShare", options_.upShare);
    requireShare("smoothing", options_.smoothing);
    if (options_.upFrames < 1) throw std::invalid_argument("frame budget: upFrames must be >= 1");
    if (options_.maxUpFrames < options_.upFrames) throw std::invalid_argument("frame budget: maxUpFrames must be >= upFrames");
    for (std::size_t i = 0; i < ladder_.size(); ++i)
        if (!(std::isfinite(ladder_[i].ms) && ladder_[i].ms > 0.0))
            throw std::invalid_argument("frame budget: rung " + std::to_string(i) + "'s ladder time must be > 0");
    const int n = int(ladder_.size());
    if (options_.startRung < -1 || options_.startRung >= n)
        throw std::invalid_argument("frame budget: start rung " + std::to_string(options_.startRung) + " is not in the ladder (0.." +
                                    std::to_string(n - 1) + ")");
    rungs_.resize(ladder_.size());
    for (Learned& r : rungs_) r.upFrames = options_.upFrames;
    rung_ = options_.startRung;
    if (rung_ < 0) {  // the ladder's own times are the only prediction before the first frame
        rung_ = n - 1;
        for (int i = 0; i < n; ++i)
            if (ladder_[std::size_t(i)].ms <= options_.fitShare * options_.budgetMs) {
                rung_ = i;
                break;
            }
    }
}

double FrameBudgetAllocator::loadRatio() const {
    if (lastMeasured_ < 0) return 1.0;  // nothing measured: believe the ladder
    const Learned& r = rungs_[std::size_t(lastMeasured_)];
    return std::max(r.ratio, r.lastRatio);
}

double FrameBudgetAllocator::predictedMs(int rung) const {
    if (rung < 0 || rung >= int(ladder_.size())) throw std::invalid_argument("frame budget: no rung " + std::to_string(rung));
    return ladder_[std::size_t(rung)].ms * loadRatio();
}

void FrameBudgetAllocator::moveTo(int rung) {
    if (rung == rung_) return;
    rung_ = rung;
    comfortable_ = 0;
    sinceChange_ = 0;
    ++changes_;
}

int FrameBudgetAllocator::observe(int frameRung, double ms) {
    if (frameRung < 0 || frameRung >= int(ladder_.size())) throw std::invalid_argument("frame budget: no rung " + std::to_string(frameRung));
    if (!(std::isfinite(ms) && ms >= 0.0)) throw std::invalid_argument("frame budget: frame time must be finite and >= 0, not " + std::to_string(ms));
    const double budget = options_.budgetMs;
    ++frames_;
    const bool over = ms > budget;
    if (over) ++over_;
    // Learn: the frame's rung's load ratio and mean time.
    Learned& l = rungs_[std::size_t(frameRung)];
    const double ratio = ms / ladder_[std::size_t(frameRung)].ms;
    const double a = options_.smoothing;
    l.ratio = l.measured ? (1.0 - a) * l.ratio + a * ratio : ratio;
    l.averageMs = l.measured ? (1.0 - a) * l.averageMs + a * ms : ms;
    l.lastRatio = ratio;
    l.measured = true;
    lastMeasured_ = frameRung;
    ++sinceChange_;

    const int n = int(ladder_.size());
    // Down at once: the current rung went over, or is predicted to.
    if ((over && frameRung == rung_) || predictedMs(rung_) > options_.stayShare * budget) {
        if (rung_ == n - 1) return rung_;  // already the cheapest: the budget's floor
        // A rung stepped up to that fails while on probation waits twice as long next time.
        if (steppedUpTo_ == rung_) {
            Learned& up = rungs_[std::size_t(rung_)];
            up.upFrames = std::min(options_.maxUpFrames, 2 * up.upFrames);
        }
        steppedUpTo_ = -1;
        int target = n - 1;
        for (int i = rung_ + 1; i < n; ++i)
            if (predictedMs(i) <= options_.fitShare * budget) {
                target = i;
                break;
            }
        moveTo(target);
        return rung_;
    }
    // A long stay on a rung stepped up to forgives its penalty.
    if (steppedUpTo_ == rung_ && sinceChange_ >= 4 * rungs_[std::size_t(rung_)].upFrames) {
        rungs_[std::size_t(rung_)].upFrames = options_.upFrames;
        steppedUpTo_ = -1;
    }
    // Up only after enough comfortable frames: to the most accurate rung predicted to fit under
    // upShare of the budget (one rung per wait would take minutes to climb a long ladder).
    if (rung_ > 0 && predictedMs(rung_ - 1) <= options_.upShare * budget) {
        int target = rung_ - 1;
        while (target > 0 && predictedMs(target - 1) <= options_.upShare * budget) --target;
        if (++comfortable_ >= rungs_[std::size_t(target)].upFrames) {
            moveTo(target);
            steppedUpTo_ = rung_;
        }
    } else {
        comfortable_ = 0;
    }
    return rung_;
}

}  // namespace throng::sim
