#include "throng/actors/KeyPoseSelection.h"

#include <algorithm>
#include <unordered_set>

namespace throng {

std::vector<std::uint32_t> selectKeyPosesGreedy(std::span<const KeyPoseDemand> demand, std::uint32_t capacity,
                                                std::span<const std::uint32_t> resident) {
    KeyPoseSelectionWorkspace workspace;
    std::vector<std::uint32_t> chosen;
    selectKeyPosesGreedy(demand, capacity, resident, workspace, chosen);
    return chosen;
}

void selectKeyPosesGreedy(std::span<const KeyPoseDemand> demand, std::uint32_t capacity,
                          std::span<const std::uint32_t> resident, KeyPoseSelectionWorkspace& w,
                          std::vector<std::uint32_t>& chosen) {
    // Per-pose flags over every pose named (flat arrays, reused: no set to allocate).
    std::uint32_t poses = 0;
    for (const KeyPoseDemand& d : demand) poses = std::max({poses, d.a + 1, d.b + 1});
    for (const std::uint32_t p : resident) poses = std::max(poses, p + 1);
    w.resident.assign(poses, 0);
    for (const std::uint32_t p : resident) w.resident[p] = 1;
    w.chosen.assign(poses, 0);
    const auto missing = [&](const KeyPoseDemand& d) { return int(!w.resident[d.a]) + int(d.b != d.a && !w.resident[d.b]); };
    w.order.resize(demand.size());
    for (std::uint32_t i = 0; i < w.order.size(); ++i) w.order[i] = i;
    // Ties broken last by position, so the order is total and a plain sort (which, unlike a stable
    // one, needs no buffer) gives the stable order.
    std::sort(w.order.begin(), w.order.end(), [&](std::uint32_t x, std::uint32_t y) {
        const KeyPoseDemand& p = demand[x];
        const KeyPoseDemand& q = demand[y];
        if (p.actors != q.actors) return p.actors > q.actors;
        const int mp = missing(p), mq = missing(q);
        if (mp != mq) return mp < mq;
        if (p.a != q.a) return p.a < q.a;
        if (p.b != q.b) return p.b < q.b;
        return x < y;
    });
    chosen.clear();
    for (const std::uint32_t i : w.order) {
        if (chosen.size() >= capacity) break;
        const KeyPoseDemand& d = demand[i];
        if (d.actors == 0) break;  // sorted: no later demand serves anyone either
        const bool needA = !w.chosen[d.a], needB = d.b != d.a && !w.chosen[d.b];
        if (chosen.size() + std::size_t(needA) + std::size_t(needB) > capacity) continue;
        if (needA) chosen.push_back(d.a), w.chosen[d.a] = 1;
        if (needB) chosen.push_back(d.b), w.chosen[d.b] = 1;
    }
}

std::uint64_t actorsServed(std::span<const KeyPoseDemand> demand, std::span<const std::uint32_t> poses) {
    const std::unordered_set<std::uint32_t> in(poses.begin(), poses.end());
    std::uint64_t served = 0;
    for (const KeyPoseDemand& d : demand)
        if (in.count(d.a) && in.count(d.b)) served += d.actors;
    return served;
}

}  // namespace throng
