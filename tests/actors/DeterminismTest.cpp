// Same scene, same steps: bitwise-identical state and draw lists with 1 thread or several.

#include <gtest/gtest.h>

#include <cstring>

#include "ActorTestScenes.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/WorkerPool.h"
#include "throng/scenegraph/Camera.h"

using namespace throng;
using namespace throng::testing;

namespace {
template <class T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}
}  // namespace

TEST(Determinism, OneThreadOrFourGiveBitwiseIdenticalResults) {
    auto one = makeRandomCrowd(5, 2000, 80.0);
    auto four = makeRandomCrowd(5, 2000, 80.0);
    ActorProcessor p1(one->crowd), p4(four->crowd);
    p4.setThreads(4);
    for (int f = 0; f < 15; ++f) {
        Camera camera;
        camera.setPerspective(1.1, 1.6, 0.1, 300.0);
        camera.setLookAt(Vec3(60.0 * std::cos(0.3 * f), 15, 60.0 * std::sin(0.3 * f)), Vec3(0.0), Vec3(0, 1, 0));
        const double t = f / 30.0;
        const auto& s1 = p1.processFrame(*one->root, camera, t);
        const auto& s4 = p4.processFrame(*four->root, camera, t);
        ASSERT_EQ(s1.skeletonNodesEvaluated, s4.skeletonNodesEvaluated);
        const Crowd::State &a = one->crowd.state(), &b = four->crowd.state();
        ASSERT_TRUE(sameBytes(a.refWorld, b.refWorld)) << "frame " << f;
        ASSERT_TRUE(sameBytes(a.sklsWorld, b.sklsWorld)) << "frame " << f;
        ASSERT_TRUE(sameBytes(a.dofs, b.dofs)) << "frame " << f;
        const auto& l1 = p1.drawList().items();
        const auto& l4 = p4.drawList().items();
        ASSERT_EQ(l1.size(), l4.size());
        for (std::size_t i = 0; i < l1.size(); ++i) {
            ASSERT_EQ(l1[i].instance, l4[i].instance);
            ASSERT_EQ(l1[i].part, l4[i].part);
            ASSERT_EQ(l1[i].drawable, l4[i].drawable);  // templates are shared between the two crowds
            ASSERT_EQ(0, std::memcmp(l1[i].worldMatrix, l4[i].worldMatrix, sizeof(Mat4))) << "item " << i;
        }
    }
}

TEST(Determinism, WorkerPoolCoversEveryIndexOnceAndRethrows) {
    WorkerPool pool(3);
    EXPECT_EQ(pool.threads(), 3u);
    std::vector<int> hits(1001, 0);
    pool.parallelFor(hits.size(), [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) ++hits[i];
    });
    for (int h : hits) ASSERT_EQ(h, 1);
    EXPECT_THROW(pool.parallelFor(10, [](std::size_t b, std::size_t) {
        if (b > 0) throw std::runtime_error("boom");
    }), std::runtime_error);
    pool.parallelFor(4, [](std::size_t, std::size_t) {});  // still usable
    EXPECT_THROW(WorkerPool(0), std::invalid_argument);
}
