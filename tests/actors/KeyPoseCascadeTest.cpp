// Key-pose caches in the cascade (seed 004): actors of the middle band are drawn from their
// template's cache when the poses they need are held, with no Skeleton node processed; the rest
// are posed and skinned as usual; the cache keeps its poses across frames; the result does not
// depend on the number of threads; without a cache and a distance nothing changes.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/actors/KeyPoseSelection.h"
#include "throng/scenegraph/Camera.h"

using namespace throng;
using namespace throng::testkit;

namespace {

// Skinned bars in a line along +Z from 4 m to 4 + 0.5 * (n - 1) m, each at its own clip time,
// seen from the origin.
struct BarLine {
    Crowd crowd;
    std::shared_ptr<const ActorTemplate> tmpl = skinnedBar();
    std::shared_ptr<KeyframeBehaviour> behaviour = std::make_shared<KeyframeBehaviour>();
    std::shared_ptr<Group> root = std::make_shared<Group>();
    Camera camera;

    explicit BarLine(int n) {
        for (int i = 0; i < n; ++i) {
            KeyframeBehaviour::Actor a;
            a.tmpl = tmpl;
            a.position = Vec3(0.3 * ((i % 5) - 2), 0, 4.0 + 0.5 * i);
            a.timeOffset = 0.037 * ((i * 7) % 53);  // spread over the 2 s clip
            root->addChild(crowd.makeActorNode(crowd.add(tmpl, behaviour, behaviour->addActor(a))));
        }
        camera.setPerspective(1.0, 1.0, 0.1, 1000.0);
        camera.setLookAt(Vec3(0, 1, 0), Vec3(0, 1, 10));
    }
    std::shared_ptr<KeyPoseCache> cache(std::uint32_t rows, KeyPoseMode mode = KeyPoseMode::Intermittent) const {
        KeyPoseCacheSettings s;
        s.rows = rows;
        s.mode = mode;
        return std::make_shared<KeyPoseCache>(tmpl, s);
    }
};

std::size_t count(const DrawList& list, Representation r) {
    std::size_t n = 0;
    for (const DrawItem& item : list.items()) n += item.representation == r;
    return n;
}

}  // namespace

TEST(KeyPoseCascade, NothingChangesWithoutBothACacheAndADistance) {
    BarLine s(60);
    ActorProcessor plain(s.crowd), cacheOnly(s.crowd), distanceOnly(s.crowd);
    cacheOnly.setKeyPoseCache(s.cache(64));
    distanceOnly.setKeyPoseDistance(10.0);
    for (double t : {0.1, 0.6}) {
        const auto plainItems = primitives((plain.processFrame(*s.root, s.camera, t), plain.drawList()));
        for (ActorProcessor* p : {&cacheOnly, &distanceOnly}) {
            const ActorFrameStatistics& st = p->processFrame(*s.root, s.camera, t);
            EXPECT_EQ(st.keyPoseBand + st.keyPoseActors + st.keyPoseUpdates + st.keyPosesHeld, 0u);
            EXPECT_EQ(count(p->drawList(), Representation::KeyPose), 0u);
            EXPECT_EQ(primitives(p->drawList()), plainItems);
        }
    }
}

TEST(KeyPoseCascade, ActorsInTheBandAreDrawnFromTheCacheWithNoSkeletonNodeProcessed) {
    BarLine s(60);
    ActorProcessor p(s.crowd);
    auto cache = s.cache(64);  // more rows than the clip has key-poses: everyone fits
    p.setKeyPoseCache(cache);
    p.setKeyPoseDistance(12.0);
    const ActorFrameStatistics& st = p.processFrame(*s.root, s.camera, 0.4);
    ASSERT_GT(st.keyPoseBand, 10u);
    EXPECT_EQ(st.keyPoseActors, st.keyPoseBand);
    EXPECT_EQ(st.keyPoseMisses, 0u);
    EXPECT_EQ(st.keyPoseUpdates, st.keyPosesHeld) << "a first frame stores every pose it holds";
    std::size_t near = 0, cached = 0;
    for (const DrawItem& item : p.drawList().items()) {
        const double distance = s.crowd.state().eyeDistance[item.actor];
        if (item.representation == Representation::KeyPose) {
            ++cached;
            EXPECT_GT(distance, 12.0);
            EXPECT_EQ(item.keyPose.source, cache.get());
            EXPECT_EQ(item.skinPalette, nullptr) << "a cached actor needs no palette of its own";
            const KeyPoseSample want = cache->sample(item.clip, item.clipTime);
            EXPECT_EQ(item.keyPose.pose[0], want.a);
            EXPECT_EQ(item.keyPose.pose[1], want.b);
            EXPECT_EQ(cache->rows().poseIn(item.keyPose.row[0]), want.a) << "the row named holds the pose";
            EXPECT_EQ(item.keyPose.skin, 0u);
        } else {
            ++near;
            EXPECT_LT(distance, 12.0);
            EXPECT_NE(item.skinPalette, nullptr);
        }
    }
    EXPECT_EQ(cached, st.keyPoseActors);
    EXPECT_EQ(st.actorsPosed, near) << "only actors nearer than the band are posed";
    EXPECT_EQ(st.skeletonNodesEvaluated, near * s.tmpl->nodeCount());
}

TEST(KeyPoseCascade, ASmallCacheHoldsThePosesMostActorsNeedAndTheRestAreSkinned) {
    BarLine s(120);
    ActorProcessor p(s.crowd);
    auto cache = s.cache(4);
    p.setKeyPoseCache(cache);
    p.setKeyPoseDistance(8.0);
    const ActorFrameStatistics& st = p.processFrame(*s.root, s.camera, 1.3);
    ASSERT_GT(st.keyPoseBand, 50u);
    EXPECT_EQ(st.keyPosesHeld, 4u);
    EXPECT_GT(st.keyPoseMisses, 0u);
    EXPECT_EQ(st.keyPoseActors + st.keyPoseMisses, st.keyPoseBand);
    // The served actors are exactly those the held poses serve, and no 4 poses serve more.
    std::vector<std::uint32_t> needs(cache->poseCount(), 0);
    for (const DrawItem& item : p.drawList().items()) {
        if (item.clip < 0) continue;
        if (s.crowd.state().eyeDistance[item.actor] * 1.0 <= 8.0) continue;
        ++needs[cache->sample(item.clip, item.clipTime).a];
    }
    std::vector<KeyPoseDemand> demand;
    for (std::uint32_t pose = 0; pose < needs.size(); ++pose)
        if (needs[pose]) demand.push_back({pose, pose, needs[pose]});
    EXPECT_EQ(actorsServed(demand, cache->rows().held()), st.keyPoseActors);
    std::sort(needs.rbegin(), needs.rend());
    EXPECT_EQ(st.keyPoseActors, std::uint64_t(needs[0] + needs[1] + needs[2] + needs[3]));
    EXPECT_EQ(count(p.drawList(), Representation::KeyPose), st.keyPoseActors);
}

TEST(KeyPoseCascade, PosesHeldStayAcrossFramesAndAreNotStoredAgain) {
    BarLine s(80);
    ActorProcessor p(s.crowd);
    p.setKeyPoseCache(s.cache(40));
    p.setKeyPoseDistance(8.0);
    const std::uint64_t first = p.processFrame(*s.root, s.camera, 0.5).keyPoseUpdates;
    EXPECT_GT(first, 0u);
    EXPECT_EQ(p.processFrame(*s.root, s.camera, 0.5).keyPoseUpdates, 0u) << "the same frame again needs nothing new";
    // A frame later (1/60 s) most actors still show the same key-pose: few new ones.
    const ActorFrameStatistics& later = p.processFrame(*s.root, s.camera, 0.5 + 1.0 / 60.0);
    EXPECT_LT(later.keyPoseUpdates, first / 2);
    EXPECT_EQ(later.keyPoseMisses, 0u);
}

TEST(KeyPoseCascade, InterpolativeActorsBlendTheTwoKeyPosesAroundTheirClipTime) {
    BarLine s(60);
    ActorProcessor p(s.crowd);
    auto cache = s.cache(64, KeyPoseMode::Interpolative);
    p.setKeyPoseCache(cache);
    p.setKeyPoseDistance(12.0);
    const ActorFrameStatistics& st = p.processFrame(*s.root, s.camera, 0.77);
    ASSERT_GT(st.keyPoseActors, 10u);
    for (const DrawItem& item : p.drawList().items()) {
        if (item.representation != Representation::KeyPose) continue;
        const KeyPoseRef& k = item.keyPose;
        EXPECT_EQ(k.pose[1], cache->firstPose(item.clip) + (k.pose[0] - cache->firstPose(item.clip) + 1) % cache->posesOf(item.clip));
        EXPECT_GE(k.blend, 0.0f);
        EXPECT_LT(k.blend, 1.0f);
        const double u = cache->timeOf(k.pose[0]) + k.blend * 2.0 / cache->posesOf(item.clip);
        EXPECT_NEAR(u, std::fmod(item.clipTime, 2.0), 1e-5) << "the blend places the actor at its clip time";
        EXPECT_EQ(cache->rows().poseIn(k.row[0]), k.pose[0]);
        EXPECT_EQ(cache->rows().poseIn(k.row[1]), k.pose[1]);
    }
}

TEST(KeyPoseCascade, TheSameWhateverTheThreads) {
    BarLine s(700);
    ActorProcessor one(s.crowd), two(s.crowd);
    two.setThreads(2);
    for (ActorProcessor* p : {&one, &two}) {
        p->setKeyPoseCache(s.cache(12, KeyPoseMode::Interpolative));
        p->setKeyPoseDistance(20.0, 1.0);
    }
    for (int frame = 0; frame < 5; ++frame) {
        const double t = 0.3 + frame * 0.05;
        const ActorFrameStatistics a = one.processFrame(*s.root, s.camera, t);
        const ActorFrameStatistics& b = two.processFrame(*s.root, s.camera, t);
        EXPECT_EQ(a.keyPoseActors, b.keyPoseActors);
        EXPECT_EQ(a.keyPoseUpdates, b.keyPoseUpdates);
        ASSERT_EQ(one.drawList().size(), two.drawList().size());
        for (std::size_t i = 0; i < one.drawList().size(); ++i) {
            const DrawItem& x = one.drawList().items()[i];
            const DrawItem& y = two.drawList().items()[i];
            ASSERT_EQ(x.actor, y.actor);
            ASSERT_EQ(x.representation, y.representation);
            ASSERT_EQ(x.keyPose.pose[0], y.keyPose.pose[0]);
            ASSERT_EQ(x.keyPose.row[0], y.keyPose.row[0]);
            ASSERT_EQ(x.keyPose.row[1], y.keyPose.row[1]);
            ASSERT_EQ(x.keyPose.blend, y.keyPose.blend);
            ASSERT_EQ(x.world, y.world);
        }
    }
}

TEST(KeyPoseCascade, TheBandHasHysteresis) {
    BarLine s(1);
    ActorProcessor p(s.crowd);
    p.setKeyPoseCache(s.cache(8));
    p.setKeyPoseDistance(20.0, 2.0);
    struct Step {
        double eyeZ;     // the actor stands at z = 4
        bool cached;
    };
    // In from 44 m, out past 18 m, in again past 22 m.
    for (const Step& step : {Step{-40, true}, Step{-15.5, true}, Step{-13.5, false}, Step{-17, false}, Step{-17.9, false},
                             Step{-18.5, true}, Step{-15.5, true}}) {
        Camera c = s.camera;
        c.setLookAt(Vec3(0, 1, step.eyeZ), Vec3(0, 1, 4));
        const ActorFrameStatistics& st = p.processFrame(*s.root, c, 0.2);
        EXPECT_EQ(st.keyPoseActors, step.cached ? 1u : 0u) << "eye at z = " << step.eyeZ << ", distance " << s.crowd.state().eyeDistance[0];
    }
}

TEST(KeyPoseCascade, BadSettingsAreRejected) {
    BarLine s(1);
    ActorProcessor p(s.crowd);
    EXPECT_THROW(p.setKeyPoseDistance(-1.0), std::invalid_argument);
    EXPECT_THROW(p.setKeyPoseDistance(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_THROW(p.setKeyPoseDistance(10.0, std::numeric_limits<double>::infinity()), std::invalid_argument);
    EXPECT_THROW(p.setKeyPoseCache(nullptr), std::invalid_argument);
    EXPECT_EQ(p.keyPoseDistance(), 0.0);
    EXPECT_TRUE(p.keyPoseCaches().empty());
}
