#include "throng/render/MorphPool.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace throng {

MorphPool::MorphPool(int slots, int keyframes, std::uint32_t views) : views_(views), keyframes_(keyframes) {
    if (slots < 0) throw std::invalid_argument("MorphPool: slots must be >= 0, not " + std::to_string(slots));
    if (keyframes <= 0 || views == 0)
        throw std::invalid_argument("MorphPool: an atlas of " + std::to_string(keyframes) + " key-frames x " +
                                    std::to_string(views) + " views has no cell");
    const std::size_t cells = static_cast<std::size_t>(keyframes) * views;
    slotOfCell_.assign(cells, -1);
    demand_.assign(cells, 0);
    score_.assign(cells, 0.0f);
    cellOfSlot_.assign(static_cast<std::size_t>(slots), -1);
    slotUsed_.assign(static_cast<std::size_t>(slots), 0);
    slotReady_.assign(static_cast<std::size_t>(slots), 1);
    wantedCells_.reserve(cells);
    candidates_.reserve(cells);
    freeSlots_.reserve(static_cast<std::size_t>(slots));
    fills_.reserve(static_cast<std::size_t>(slots));
}

std::size_t MorphPool::cellIndex(int keyframe, std::uint32_t view) const {
    if (keyframe < 0 || keyframe >= keyframes_ || view >= views_)
        throw std::out_of_range("MorphPool: cell (key-frame " + std::to_string(keyframe) + ", view " + std::to_string(view) +
                                ") is outside the atlas of " + std::to_string(keyframes_) + " x " + std::to_string(views_));
    return static_cast<std::size_t>(keyframe) * views_ + view;
}

void MorphPool::beginFrame() {
    for (std::uint32_t c : wantedCells_) demand_[c] = 0;
    wantedCells_.clear();
    fills_.clear();
    stats_ = {};
    ++frame_;  // frame 0 is "never": a fresh slot is the least recently used
}

void MorphPool::want(int keyframe, std::uint32_t view) {
    const std::size_t c = cellIndex(keyframe, view);
    if (demand_[c]++ == 0) wantedCells_.push_back(static_cast<std::uint32_t>(c));
}

std::span<const MorphFill> MorphPool::resolve(int budget) {
    fills_.clear();
    candidates_.clear();
    stats_.wanted = wantedCells_.size();
    // Each cell's demand, smoothed over frames: the crowd's phases and headings make it steady
    // even though each actor's key-frame changes every few frames.
    for (std::size_t c = 0; c < score_.size(); ++c) score_[c] = score_[c] * kScoreDecay + static_cast<float>(demand_[c]);
    for (std::uint32_t c : wantedCells_) {
        const int slot = slotOfCell_[c];
        if (slot >= 0) {
            slotUsed_[static_cast<std::size_t>(slot)] = frame_;
            ++stats_.resident;
        } else {
            candidates_.push_back(c);
        }
    }
    // Victims, best first: empty slots, then resident cells by rising score (least recently used
    // on a tie).
    freeSlots_.clear();
    for (int s = 0; s < slots(); ++s)
        if (slotReady_[static_cast<std::size_t>(s)]) freeSlots_.push_back(s);  // a pending slot is taken
    const auto slotScore = [&](int s) {
        const int c = cellOfSlot_[static_cast<std::size_t>(s)];
        return c < 0 ? -1.0f : score_[static_cast<std::size_t>(c)];
    };
    std::stable_sort(freeSlots_.begin(), freeSlots_.end(), [&](int a, int b) {
        const float sa = slotScore(a), sb = slotScore(b);
        if (sa != sb) return sa < sb;
        return slotUsed_[static_cast<std::size_t>(a)] < slotUsed_[static_cast<std::size_t>(b)];
    });
    // The candidates by falling score; cell index (key-frame, then view) breaks ties.
    std::sort(candidates_.begin(), candidates_.end(), [&](std::uint32_t a, std::uint32_t b) {
        return score_[a] != score_[b] ? score_[a] > score_[b] : a < b;
    });
    const std::size_t limit = budget >= 0 ? std::min(candidates_.size(), static_cast<std::size_t>(budget)) : candidates_.size();
    std::size_t made = 0;
    for (std::size_t i = 0; i < candidates_.size() && made < limit && made < freeSlots_.size(); ++i) {
        const std::uint32_t c = candidates_[i];
        const int slot = freeSlots_[made];
        const int old = cellOfSlot_[static_cast<std::size_t>(slot)];
        // A resident cell gives way only to a clearly more wanted one (no churn between equals).
        if (old >= 0 && !(score_[c] > kReplaceMargin * score_[static_cast<std::size_t>(old)])) break;
        if (old >= 0) {
            slotOfCell_[static_cast<std::size_t>(old)] = -1;
            ++stats_.evicted;
        }
        cellOfSlot_[static_cast<std::size_t>(slot)] = static_cast<int>(c);
        slotOfCell_[c] = slot;
        slotUsed_[static_cast<std::size_t>(slot)] = frame_;
        fills_.push_back({c % views_, static_cast<int>(c / views_), slot});
        ++made;
    }
    stats_.made = made;
    stats_.deferred = candidates_.size() - made;
    return fills_;
}

int MorphPool::slotOf(int keyframe, std::uint32_t view) const {
    const int slot = slotOfCell_[cellIndex(keyframe, view)];
    return slot >= 0 && slotReady_[static_cast<std::size_t>(slot)] ? slot : -1;
}

void MorphPool::setPending(int slot) {
    if (slot < 0 || slot >= slots()) throw std::out_of_range("MorphPool::setPending: no slot " + std::to_string(slot));
    slotReady_[static_cast<std::size_t>(slot)] = 0;
}

void MorphPool::setReady(int slot) {
    if (slot < 0 || slot >= slots()) throw std::out_of_range("MorphPool::setReady: no slot " + std::to_string(slot));
    slotReady_[static_cast<std::size_t>(slot)] = 1;
}

void MorphPool::clear() {
    std::fill(slotOfCell_.begin(), slotOfCell_.end(), -1);
    std::fill(cellOfSlot_.begin(), cellOfSlot_.end(), -1);
    std::fill(slotUsed_.begin(), slotUsed_.end(), 0);
    std::fill(slotReady_.begin(), slotReady_.end(), 1);
    std::fill(score_.begin(), score_.end(), 0.0f);
}

}  // namespace throng
