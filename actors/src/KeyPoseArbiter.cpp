#include "throng/actors/KeyPoseArbiter.h"

#include "throng/actors/KeyPoseCache.h"

namespace throng {

void addKeyPoseDemands(std::vector<KeyPoseDemand>& combined, std::span<const KeyPoseDemand> part) {
    // Both sorted by first pose: merged in place from the back.
    std::size_t added = 0;
    {
        std::size_t i = 0;
        for (const KeyPoseDemand& d : part) {
            while (i < combined.size() && combined[i].a < d.a) ++i;
            if (i < combined.size() && combined[i].a == d.a && combined[i].b == d.b) combined[i].actors += d.actors;
            else ++added;
        }
    }
    if (added == 0) return;
    std::size_t write = combined.size() + added, i = combined.size();
    combined.resize(write);
    for (std::size_t k = part.size(); k-- > 0;) {
        const KeyPoseDemand& d = part[k];
        while (i > 0 && (combined[i - 1].a > d.a || (combined[i - 1].a == d.a && combined[i - 1].b > d.b))) combined[--write] = combined[--i];
        if (i > 0 && combined[i - 1].a == d.a && combined[i - 1].b == d.b) continue;  // added above
        combined[--write] = d;
    }
}

KeyPoseSelectionCounts KeyPoseSelector::select(KeyPoseCache& cache, std::span<const KeyPoseDemand> demand, std::uint64_t frame) {
    KeyPoseSelectionCounts counts;
    cache.recordDemand(demand);
    if (demand.empty()) return counts;
    poseNeeded_.assign(cache.poseCount(), 0);
    for (const KeyPoseDemand& d : demand) poseNeeded_[d.a] = poseNeeded_[d.b] = 1;
    for (const std::uint8_t x : poseNeeded_) counts.wanted += x;
    KeyPoseRows& rows = cache.rows();
    rows.held(resident_);
    selectKeyPosesGreedy(demand, rows.rowCount(), resident_, workspace_, chosen_);
    counts.updates = rows.hold(chosen_, frame);
    // The poses serving a demand (both held) are used this frame, as they serve its actors.
    for (const KeyPoseDemand& d : demand)
        if (rows.rowOf(d.a) != KeyPoseRows::kNone && rows.rowOf(d.b) != KeyPoseRows::kNone) rows.touch(d.a, frame), rows.touch(d.b, frame);
    counts.held = rows.heldCount();
    return counts;
}

}  // namespace throng
