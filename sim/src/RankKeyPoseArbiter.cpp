#include "throng/sim/RankKeyPoseArbiter.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "throng/actors/KeyPoseCache.h"
#include "throng/scenegraph/ByteStream.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/Ranks.h"

namespace throng::sim {

RankKeyPoseArbiter::RankKeyPoseArbiter(Ranks& ranks, int tag) : ranks_(ranks), tag_(tag) {}

KeyPoseSelectionCounts RankKeyPoseArbiter::settle(std::span<const std::vector<KeyPoseDemand>> demands,
                                                  std::span<const std::shared_ptr<KeyPoseCache>> caches, std::uint64_t frame) {
    // This rank's demands: per cache, a count and the demands.
    Bytes mine;
    ByteWriter out(mine);
    out.put(std::uint32_t(demands.size()));
    for (const std::vector<KeyPoseDemand>& d : demands) {
        out.put(std::uint32_t(d.size()));
        out.putSpan(std::span<const KeyPoseDemand>(d));
    }
    const Stopwatch wait;
    const std::vector<Bytes> all = ranks_.gather(mine, tag_, "key-pose demands");
    waitMs_ += wait.elapsedMs();
    KeyPoseSelectionCounts counts;
    Bytes rows;
    if (ranks_.rank() == 0) {
        // Each cache's demands of every rank added, then one selection, as one process makes it.
        std::vector<ByteReader> in;
        for (std::size_t r = 0; r < all.size(); ++r) {
            in.emplace_back(all[r], "rank " + std::to_string(r) + "'s key-pose demands");
            if (in.back().get<std::uint32_t>("the cache count") != caches.size())
                throw RankError(int(r), in.back().source() + " are for another number of caches than rank 0's " + std::to_string(caches.size()));
        }
        ByteWriter rowsOut(rows);
        for (std::size_t ci = 0; ci < caches.size(); ++ci) {
            sum_.clear();
            for (std::size_t r = 0; r < in.size(); ++r) {
                try {
                    const std::uint32_t n = in[r].get<std::uint32_t>("a demand count");
                    in[r].require(std::size_t(n) * sizeof(KeyPoseDemand), "the demands");
                    part_.resize(n);
                    for (KeyPoseDemand& d : part_) d = in[r].get<KeyPoseDemand>("a demand");
                    for (std::size_t k = 0; k < n; ++k)
                        if (part_[k].a >= caches[ci]->poseCount() || part_[k].b >= caches[ci]->poseCount() || (k > 0 && part_[k].a <= part_[k - 1].a))
                            throw std::invalid_argument(in[r].source() + ": demand " + std::to_string(k) + " of cache " + std::to_string(ci) +
                                                        " names a pose out of range or out of order");
                } catch (const std::invalid_argument& e) {
                    throw RankError(int(r), e.what());
                }
                addKeyPoseDemands(sum_, part_);
            }
            const KeyPoseSelectionCounts c = selector_.select(*caches[ci], sum_, frame);
            counts.wanted += c.wanted, counts.updates += c.updates, counts.held += c.held;
            rowsOut.putSpan(caches[ci]->rows().rowPoses());
        }
    }
    const Stopwatch rowsWait;
    rows = ranks_.broadcast(rows, tag_ + 1, "key-pose rows");
    waitMs_ += rowsWait.elapsedMs();
    if (ranks_.rank() != 0) {
        ByteReader in(rows, "rank 0's key-pose rows");
        try {
            for (const auto& cache : caches) {
                const std::span<const std::byte> poses = in.take(std::size_t(cache->rowCount()) * sizeof(std::uint32_t), "a cache's rows");
                rowPoses_.resize(cache->rowCount());
                std::memcpy(rowPoses_.data(), poses.data(), poses.size());
                cache->rows().copyRows(rowPoses_);
            }
        } catch (const std::invalid_argument& e) {
            throw RankError(0, e.what());
        }
    }
    return counts;
}

}  // namespace throng::sim
