// Same scene, same steps: bitwise-identical state, draw lists and FMULT counts with 1 thread or
// several, under both processing methods; and the chunked loops they run on.

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <span>
#include <mutex>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/ThreadTeam.h"

using namespace throng;
using namespace throng::testkit;

namespace {
template <class T>
bool sameBytes(std::span<const T> a, std::span<const T> b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// Runs 15 frames of one random crowd per thread count and checks every thread count against the
// first; the last crowd defers its actors' state until shown (Crowd::deferStateUntilShown), which
// must not change a bit either.
void expectSameWithThreads(Processing processing, bool counting) {
    const unsigned threads[] = {1, 2, 4, 2};
    const bool deferred[] = {false, false, false, true};
    std::vector<std::unique_ptr<RandomCrowd>> worlds;
    std::vector<std::unique_ptr<ActorProcessor>> processors;
    for (std::size_t k = 0; k < std::size(threads); ++k) {
        const unsigned n = threads[k];
        worlds.push_back(makeRandomCrowd(5, 2000, 80.0, deferred[k]));
        processors.push_back(std::make_unique<ActorProcessor>(worlds.back()->crowd));
        processors.back()->setThreads(n);
        processors.back()->setProcessing(processing);
        processors.back()->counter().setEnabled(counting);
    }
    for (int f = 0; f < 15; ++f) {
        Camera camera;
        camera.setPerspective(1.1, 1.6, 0.1, 300.0);
        camera.setLookAt(Vec3(60.0 * std::cos(0.3 * f), 15, 60.0 * std::sin(0.3 * f)), Vec3(0.0), Vec3(0, 1, 0));
        const double t = f / 30.0;
        for (std::size_t k = 0; k < processors.size(); ++k) processors[k]->processFrame(*worlds[k]->root, camera, t);
        const ActorFrameStatistics& s1 = processors[0]->statistics();
        const Crowd::State& a = worlds[0]->crowd.state();
        const auto listed = processors[0]->drawList().items();
        const std::vector<DrawItem> l1(listed.begin(), listed.end());
        ASSERT_GT(l1.size(), 0u);
        for (std::size_t k = 1; k < processors.size(); ++k) {
            SCOPED_TRACE(::testing::Message() << threads[k] << " threads" << (deferred[k] ? ", state deferred" : "") << ", frame " << f);
            // Every actor of the random crowd is present: the first frame writes every deferred state.
            ASSERT_EQ(worlds[k]->crowd.deferredStates(), 0u);
            const ActorFrameStatistics& sk = processors[k]->statistics();
            ASSERT_EQ(s1.skeletonNodesEvaluated, sk.skeletonNodesEvaluated);
            ASSERT_EQ(s1.spheresTested, sk.spheresTested);
            ASSERT_EQ(s1.lodDistances, sk.lodDistances);
            ASSERT_EQ(s1.fmultTotal, sk.fmultTotal);
            if (counting) {
                ASSERT_GT(sk.fmultTotal, 0u);
            }
            const Crowd::State& b = worlds[k]->crowd.state();
            ASSERT_TRUE(sameBytes<Mat4>(a.refWorld, b.refWorld));
            ASSERT_TRUE(sameBytes<Mat4>(a.sklsWorld, b.sklsWorld));
            ASSERT_TRUE(sameBytes<float>(a.dofs, b.dofs));
            const auto listedK = processors[k]->drawList().items();
            const std::vector<DrawItem> lk(listedK.begin(), listedK.end());
            ASSERT_EQ(l1.size(), lk.size());
            for (std::size_t i = 0; i < l1.size(); ++i) {
                ASSERT_EQ(l1[i].instance, lk[i].instance);
                ASSERT_EQ(l1[i].part, lk[i].part);
                ASSERT_EQ(l1[i].actor, lk[i].actor);
                ASSERT_EQ(l1[i].drawable, lk[i].drawable);  // templates are shared between the crowds
                ASSERT_EQ(0, std::memcmp(&l1[i].world.translation, &lk[i].world.translation, sizeof(Vec3))) << "item " << i;
                ASSERT_EQ(0, std::memcmp(&l1[i].world.linear, &lk[i].world.linear, sizeof(glm::mat3))) << "item " << i;
                ASSERT_EQ(l1[i].skinPaletteSize, lk[i].skinPaletteSize);
                if (l1[i].skinPaletteSize) {
                    ASSERT_EQ(0, std::memcmp(l1[i].skinPalette, lk[i].skinPalette, l1[i].skinPaletteSize * sizeof(glm::mat4)));
                }
            }
        }
    }
}
}  // namespace

TEST(Determinism, ActorProcessingIsBitwiseIdenticalWithOneTwoOrFourThreads) {
    expectSameWithThreads(Processing::Actor, false);
}

TEST(Determinism, TraditionalProcessingIsBitwiseIdenticalWithOneTwoOrFourThreads) {
    expectSameWithThreads(Processing::Traditional, false);
}

TEST(Determinism, FmultCountsAreTheSameWithThreads) {
    expectSameWithThreads(Processing::Actor, true);
    expectSameWithThreads(Processing::Traditional, true);
}

TEST(Determinism, ChunksCoverEveryIndexOnceWithTheSameCutWhateverTheThreads) {
    for (unsigned threads : {1u, 2u, 4u}) {
        ThreadTeam team(threads);
        EXPECT_EQ(team.threads(), threads);
        std::vector<int> hits(1001, 0);
        std::mutex m;
        std::vector<std::array<std::size_t, 3>> cuts;
        team.run([&] {
            forEachChunk(hits.size(), 64, [&](std::size_t c, std::size_t b, std::size_t e) {
                for (std::size_t i = b; i < e; ++i) ++hits[i];
                std::lock_guard lock(m);
                cuts.push_back({c, b, e});
            });
        });
        for (int h : hits) ASSERT_EQ(h, 1);
        ASSERT_EQ(cuts.size(), chunkCount(1001, 64));
        for (const auto& [c, b, e] : cuts) {
            EXPECT_EQ(b, c * 64);
            EXPECT_EQ(e, std::min<std::size_t>(1001, (c + 1) * 64));
        }
    }
}

TEST(Determinism, ChunkedLoopsRethrowAndRejectBadArguments) {
    ThreadTeam team(2);
    std::atomic<int> ran{0};
    EXPECT_THROW(team.run([&] {
        forEachChunk(100, 10, [&](std::size_t c, std::size_t, std::size_t) {
            ++ran;
            if (c == 3) throw std::runtime_error("boom");
        });
    }), std::runtime_error);
    team.run([&] { forEachChunk(4, 1, [](std::size_t, std::size_t, std::size_t) {}); });  // still usable
    EXPECT_THROW(ThreadTeam(0), std::invalid_argument);
    EXPECT_THROW(forEachChunk(10, 0, [](std::size_t, std::size_t, std::size_t) {}), std::invalid_argument);
    Crowd crowd;
    ActorProcessor p(crowd);
    EXPECT_THROW(p.setThreads(0), std::invalid_argument);
}
