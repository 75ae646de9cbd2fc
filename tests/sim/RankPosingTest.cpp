// Ranks that each pose their share of one crowd (run by CTest under mpiexec with 2 and 3 processes,
// and plainly as one): their key-pose caches settled by RankKeyPoseArbiter, their draw items
// gathered to rank 0 as records and merged there, item for item the list of one process holding
// every actor (rank 0 builds that one too, to compare). Every rank runs the same calls.

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawRecords.h"
#include "throng/sim/RankKeyPoseArbiter.h"
#include "throng/sim/Ranks.h"
#include "throng/testkit/CachedBars.h"

namespace throng::sim {
namespace {

// Skinned bars in one group with a key-pose cache too small for every pose wanted.
std::unique_ptr<testkit::CachedBars> bars() { return testkit::cachedBars(160, 6); }

}  // namespace

TEST(RankPosing, RanksPosingTheirShareDrawWhatOneProcessDraws) {
    Ranks ranks;
    const int n = ranks.size(), me = ranks.rank();
    auto mine = bars();
    mine->behaviour->here.assign(160, 0);
    for (std::size_t i = 0; i < 160; ++i) mine->behaviour->here[i] = int(i % std::size_t(n)) == me;
    RankKeyPoseArbiter arbiter(ranks, 300);
    mine->processor->setKeyPoseArbiter(&arbiter);
    auto whole = me == 0 ? bars() : nullptr;
    DrawRecordMerger merger;
    Camera camera;
    camera.setPerspective(1.2, 1.0, 0.1, 1000.0);
    std::uint64_t cached = 0, missed = 0;
    for (int f = 0; f < 10; ++f) {
        camera.setLookAt(Vec3(0.3 * f, 1.0, -2.0 + 0.8 * f), Vec3(0.3 * f, 1.0, 30.0));
        const double time = 0.13 * f;
        const ActorFrameStatistics share = mine->processor->processFrame(*mine->root, camera, time);
        Bytes records;
        writeDrawRecords(mine->processor->drawList(), mine->refs, records);
        Bytes stats(sizeof share);
        std::memcpy(stats.data(), &share, sizeof share);
        const std::vector<Bytes> all = ranks.gather(records, 302, "draw records");
        const std::vector<Bytes> shares = ranks.gather(stats, 303, "statistics");
        if (me != 0) continue;
        SCOPED_TRACE("frame " + std::to_string(f) + " of " + std::to_string(n) + " rank(s)");
        const ActorFrameStatistics one = whole->processor->processFrame(*whole->root, camera, time);
        DrawList merged;
        const std::vector<std::span<const std::byte>> messages(all.begin(), all.end());
        merger.merge(messages, mine->refs, merged);
        const DrawList& expected = whole->processor->drawList();
        ASSERT_EQ(merged.size(), expected.size());
        auto m = merged.items().begin();
        for (const DrawItem& e : expected.items()) {
            const DrawItem& i = *m++;
            ASSERT_EQ(i.actor, e.actor);
            EXPECT_EQ(i.representation, e.representation) << "actor " << e.actor;
            EXPECT_TRUE(i.world == e.world);
            ASSERT_EQ(i.skinPaletteSize, e.skinPaletteSize);
            for (std::uint32_t j = 0; j < e.skinPaletteSize; ++j) EXPECT_EQ(i.skinPalette[j], e.skinPalette[j]);
            if (e.representation != Representation::KeyPose) continue;
            for (int k = 0; k < 2; ++k) EXPECT_EQ(i.keyPose.row[k], e.keyPose.row[k]) << "actor " << e.actor;
        }
        ActorFrameStatistics sum;
        for (const Bytes& b : shares) {
            ActorFrameStatistics s;
            ASSERT_EQ(b.size(), sizeof s);
            std::memcpy(&s, b.data(), sizeof s);
            addShare(sum, s);
        }
        EXPECT_EQ(sum.keyPoseActors, one.keyPoseActors);
        EXPECT_EQ(sum.keyPoseMisses, one.keyPoseMisses);
        ActorFrameStatistics rank0;  // the selection's counts are rank 0's (addShare leaves them)
        std::memcpy(&rank0, shares[0].data(), sizeof rank0);
        EXPECT_EQ(rank0.keyPosesHeld, one.keyPosesHeld);
        EXPECT_EQ(rank0.keyPoseUpdates, one.keyPoseUpdates);
        EXPECT_EQ(sum.b, one.b);
        cached += one.keyPoseActors, missed += one.keyPoseMisses;
    }
    if (me == 0) {
        EXPECT_GT(cached, 50u) << "the frames cover actors drawn from the cache";
        EXPECT_GT(missed, 20u) << "the frames cover actors whose poses did not fit";
    }
}

}  // namespace throng::sim
