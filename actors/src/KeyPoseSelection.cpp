#include "throng/actors/KeyPoseSelection.h"

#include <algorithm>
#include <unordered_set>

namespace throng {

std::vector<std::uint32_t> selectKeyPosesGreedy(std::span<const KeyPoseDemand> demand, std::uint32_t capacity,
                                                std::span<const std::uint32_t> resident) {
    const std::unordered_set<std::uint32_t> wasResident(resident.begin(), resident.end());
    const auto missing = [&](const KeyPoseDemand& d) {
        return int(!wasResident.count(d.a)) + int(d.b != d.a && !wasResident.count(d.b));
    };
    std::vector<std::uint32_t> order(demand.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
        const KeyPoseDemand& p = demand[x];
        const KeyPoseDemand& q = demand[y];
        if (p.actors != q.actors) return p.actors > q.actors;
        const int mp = missing(p), mq = missing(q);
        if (mp != mq) return mp < mq;
        if (p.a != q.a) return p.a < q.a;
        return p.b < q.b;
    });
    std::vector<std::uint32_t> chosen;
    std::unordered_set<std::uint32_t> in;
    for (const std::uint32_t i : order) {
        if (chosen.size() >= capacity) break;
        const KeyPoseDemand& d = demand[i];
        if (d.actors == 0) break;  // sorted: no later demand serves anyone either
        const bool needA = !in.count(d.a), needB = d.b != d.a && !in.count(d.b);
        if (chosen.size() + std::size_t(needA) + std::size_t(needB) > capacity) continue;
        if (needA) chosen.push_back(d.a), in.insert(d.a);
        if (needB) chosen.push_back(d.b), in.insert(d.b);
    }
    return chosen;
}

std::uint64_t actorsServed(std::span<const KeyPoseDemand> demand, std::span<const std::uint32_t> poses) {
    const std::unordered_set<std::uint32_t> in(poses.begin(), poses.end());
    std::uint64_t served = 0;
    for (const KeyPoseDemand& d : demand)
        if (in.count(d.a) && in.count(d.b)) served += d.actors;
    return served;
}

}  // namespace throng
