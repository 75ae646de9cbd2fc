// The cascade's jobs alone: each refuses to run on inputs it cannot use (naming itself and the
// problem), single jobs on hand-made inputs, and the jobs chained by hand reproduce what the
// ActorProcessor draws and classifies on the same crowd.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "throng/actors/ActorGroup.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/cascade/BehavioursJob.h"
#include "throng/actors/cascade/DrawListJob.h"
#include "throng/actors/cascade/InternalCullingJob.h"
#include "throng/actors/cascade/KeyPoseSelectingJob.h"
#include "throng/actors/cascade/ReferencePointsJob.h"
#include "throng/actors/cascade/RefpointCullingJob.h"
#include "throng/actors/cascade/RefpointOcclusionJob.h"
#include "throng/actors/cascade/RefpointPlacementJob.h"
#include "throng/actors/cascade/SkeletalLodJob.h"
#include "throng/actors/cascade/SkeletonRootCullingJob.h"
#include "throng/actors/cascade/SkeletonRootsJob.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/testkit/ActorTestScenes.h"
#include "throng/testkit/Cameras.h"

using namespace throng;
using namespace throng::cascade;

namespace {

// Seed humanoids walking in place on a square of `extent` metres around the origin, all in one
// actor group under a plain group (so every member reaches CULL 1 pending when the view crosses it).
struct GroupedCrowd {
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::shared_ptr<ActorGroup> group;
    std::vector<ActorId> ids;

    GroupedCrowd(int actors, double extent, std::uint64_t seed) {
        static const auto humanoid = makeSeedHumanoid();
        auto keyframes = std::make_shared<KeyframeBehaviour>(std::vector<double>{30.0, 1e9});
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
        for (int i = 0; i < actors; ++i) {
            KeyframeBehaviour::Actor a;
            a.tmpl = humanoid;
            a.clip = static_cast<int>(unit(rng) * double(humanoid->clips().size()));
            a.timeOffset = 5.0 * unit(rng);
            a.position = Vec3(extent * u(rng), 0.0, extent * u(rng));
            a.heading = 6.3 * unit(rng);
            ids.push_back(crowd.add(humanoid, keyframes, keyframes->addActor(a)));
        }
        group = crowd.makeGroupNode(ids);
        root->addChild(group);
    }
};

// The camera of the chained test: inside the crowd, so the group's bound crosses the view.
Camera streetCamera() { return testkit::lookingAt(Vec3(0.0, 1.7, 5.0), Vec3(10.0, 1.0, -40.0), {1.0, 1.5, 0.1, 120.0}); }

// What a draw item shows, bit for bit, sortable.
using ItemKey = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, const void*, std::vector<unsigned char>>;

std::vector<ItemKey> itemKeys(const DrawList& list) {
    std::vector<ItemKey> keys;
    for (const DrawItem& i : list.items()) {
        // The transform's members one by one (the struct has padding), then the palette.
        constexpr std::size_t kWorld = sizeof(Vec3) + sizeof(glm::mat3);
        std::vector<unsigned char> bits(kWorld + i.skinPaletteSize * sizeof(glm::mat4));
        std::memcpy(bits.data(), &i.world.translation, sizeof(Vec3));
        std::memcpy(bits.data() + sizeof(Vec3), &i.world.linear, sizeof(glm::mat3));
        if (i.skinPaletteSize) std::memcpy(bits.data() + kWorld, i.skinPalette, i.skinPaletteSize * sizeof(glm::mat4));
        keys.emplace_back(i.actor, i.part, i.lodLevel, i.drawable, std::move(bits));
    }
    std::sort(keys.begin(), keys.end());
    return keys;
}

// The invalid_argument a job's run throws, or "" when it runs.
template <class Run>
std::string refusal(Run&& run) {
    try {
        run();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(CascadeJobs, ChainedByHandDrawAndClassifyAsTheProcessorDoes) {
    GroupedCrowd scene(600, 80.0, 7);
    const Camera camera = streetCamera();
    const double time = 1.25;
    ActorProcessor processor(scene.crowd);
    const ActorFrameStatistics expected = processor.processFrame(*scene.root, camera, time);
    const auto expectedItems = itemKeys(processor.drawList());
    const std::vector<ActorClass> expectedClasses = scene.crowd.state().actorClass;
    ASSERT_GT(expected.a, 0u);  // the view crosses the crowd: some rejected, some drawn
    ASSERT_GT(expected.c3_1 + expected.c3_2, 0u);
    ASSERT_GT(expectedItems.size(), 0u);

    // The same frame, job by job, with the processor's default settings.
    Crowd::State& s = scene.crowd.state();
    ActorFrameStatistics stats;
    DrawList list;
    PhaseLoop loop;
    loop.begin(stats, nullptr, &list);
    const Frustum frustum = camera.frustum();
    const Vec3 eye = camera.eye();
    const std::vector<std::pair<const ActorTemplate*, std::shared_ptr<const Drawable>>> impostors;
    const std::vector<std::shared_ptr<KeyPoseCache>> caches;
    Settings settings;
    settings.impostors = &impostors;
    settings.keyPoseCaches = &caches;

    ReferencePointsJob{&scene.crowd, FrameContext{time, 0.0, 0, nullptr}}.run(loop);
    RefpointPlacementJob{&s, scene.ids, Mat4(1.0), true, BoundingSphere(), s.refWorld, s.refSphereWorld}.run(loop);
    std::vector<Candidate> candidates;
    for (std::uint32_t m = 0; m < scene.ids.size(); ++m)
        candidates.push_back(Candidate{scene.ids[m], scene.group.get(), m, Frustum::kAllPlanes, kPending});
    std::vector<std::uint32_t> survivors;
    RefpointCullingJob::Scratch cullScratch;
    RefpointCullingJob{&s, &frustum, eye, candidates, &survivors, s.actorClass, &cullScratch}.run(loop);
    SkeletonRootsJob{&s, candidates, survivors, eye, time, true, 1.0, s.root, s.sklsWorld}.run(loop);
    std::vector<std::uint8_t> impostorTier, keyPoseTier;
    SurvivorDecisions decisions;
    SkeletonRootCullingJob{&s,           &frustum, eye, time, &settings, nullptr, candidates, survivors, &impostorTier, &keyPoseTier,
                           s.actorClass, s.eyeDistance, &decisions}
        .run(loop);
    PosedActors posed;
    SkeletalLodJob{&s, candidates, survivors, &decisions, true, &posed}.run(loop);
    BehavioursJob{&s, candidates, survivors, time, &posed, s.dofs}.run(loop);
    InternalVisibility visibility;
    InternalCullingJob{&s, &frustum, candidates, survivors, &decisions, &posed, s.actorClass, &visibility}.run(loop);
    DrawListJob{&s, &frustum, time, &settings, candidates, survivors, &decisions, &posed, &visibility}.run(loop);

    EXPECT_EQ(testkit::classCounts(stats), testkit::classCounts(expected));
    EXPECT_EQ(stats.actorsPosed, expected.actorsPosed);
    EXPECT_EQ(stats.skeletonNodesEvaluated, expected.skeletonNodesEvaluated);
    EXPECT_EQ(stats.drawItems, expected.drawItems);
    EXPECT_TRUE(s.actorClass == expectedClasses);
    const auto items = itemKeys(list);
    ASSERT_EQ(items.size(), expectedItems.size());
    for (std::size_t i = 0; i < items.size(); ++i) {
        const auto& [actor, part, level, drawable, bits] = items[i];
        const auto& [xActor, xPart, xLevel, xDrawable, xBits] = expectedItems[i];
        ASSERT_TRUE(actor == xActor && part == xPart && level == xLevel && drawable == xDrawable)
            << "item " << i << ": actor " << actor << " part " << part << " level " << level << ", the processor's actor " << xActor
            << " part " << xPart << " level " << xLevel;
        ASSERT_TRUE(bits == xBits) << "item " << i << " (actor " << actor << " part " << part << "): transform or palette differs";
    }
}

TEST(CascadeJobs, EveryJobRefusesToRunWithoutItsInputsNamingItself) {
    ActorFrameStatistics stats;
    PhaseLoop loop;
    EXPECT_NE(refusal([&] { ReferencePointsJob{}.run(loop); }).find("the loop has no frame"), std::string::npos);
    loop.begin(stats, nullptr, nullptr);
    const std::vector<std::pair<std::string, std::string>> refusals = {
        {"ReferencePointsJob", refusal([&] { ReferencePointsJob{}.run(loop); })},
        {"RefpointPlacementJob", refusal([&] { RefpointPlacementJob{}.run(loop); })},
        {"RefpointCullingJob", refusal([&] { RefpointCullingJob{}.run(loop); })},
        {"RefpointOcclusionJob", refusal([&] { RefpointOcclusionJob{}.run(loop); })},
        {"SkeletonRootsJob", refusal([&] { SkeletonRootsJob{}.run(loop); })},
        {"SkeletonRootCullingJob", refusal([&] { SkeletonRootCullingJob{}.run(loop); })},
        {"KeyPoseSelectingJob", refusal([&] { KeyPoseSelectingJob{}.run(loop); })},
        {"SkeletalLodJob", refusal([&] { SkeletalLodJob{}.run(loop); })},
        {"BehavioursJob", refusal([&] { BehavioursJob{}.run(loop); })},
        {"InternalCullingJob", refusal([&] { InternalCullingJob{}.run(loop); })},
        {"DrawListJob", refusal([&] { DrawListJob{}.run(loop); })},
    };
    for (const auto& [job, message] : refusals) EXPECT_EQ(message.rfind(job + ": ", 0), 0u) << job << " said: " << message;
    EXPECT_NE(refusals.back().second.find("no draw list"), std::string::npos);
}

TEST(CascadeJobs, ValidateCatchesArraysOfTheWrongSize) {
    GroupedCrowd scene(3, 10.0, 1);
    Crowd::State& s = scene.crowd.state();
    const Frustum frustum = streetCamera().frustum();
    std::vector<Candidate> candidates;
    std::vector<std::uint32_t> survivors;
    RefpointCullingJob::Scratch scratch;
    RefpointCullingJob cull{&s, &frustum, Vec3(0.0), candidates, &survivors, s.actorClass, &scratch};
    EXPECT_TRUE(cull.validate());
    std::vector<ActorClass> shortClasses(2);
    cull.actorClass = shortClasses;
    EXPECT_FALSE(cull.validate());
    EXPECT_NE(std::string(cull.problem()).find("actorClass"), std::string::npos);

    SurvivorDecisions decisions;
    survivors = {0};
    candidates.push_back(Candidate{0, scene.group.get(), 0, 0, kInside});
    PosedActors posed;
    SkeletalLodJob lod{&s, candidates, survivors, &decisions, true, &posed};
    EXPECT_FALSE(lod.validate());  // no decision for the survivor
    decisions.outcome = {kPosed};
    decisions.detail2 = {1.0};
    decisions.level = {0};
    EXPECT_TRUE(lod.validate());

    std::vector<float> fewDofs(3);
    BehavioursJob pose{&s, candidates, survivors, 0.0, &posed, fewDofs};
    EXPECT_FALSE(pose.validate());
    pose.dofs = s.dofs;
    EXPECT_TRUE(pose.validate());
}

TEST(CascadeJobs, RefpointCullingRejectsWhatIsBehindTheEyeAndKeepsTheOrder) {
    GroupedCrowd scene(4, 1.0, 3);
    Crowd::State& s = scene.crowd.state();
    // Actors 0 and 2 ahead of the eye, 1 and 3 behind it (the camera looks down -z from the origin).
    const double z[] = {-20.0, 30.0, -40.0, 60.0};
    for (ActorId id = 0; id < 4; ++id) s.refSphereWorld[id] = BoundingSphere(Vec3(0.0, 1.0, z[id]), 1.0);
    const Camera camera = testkit::lookingAt(Vec3(0.0, 1.0, 0.0), Vec3(0.0, 1.0, -10.0), {1.0, 1.5, 0.1, 100.0});
    const Frustum frustum = camera.frustum();
    std::vector<Candidate> candidates;
    for (std::uint32_t m = 0; m < 4; ++m) candidates.push_back(Candidate{m, scene.group.get(), m, Frustum::kAllPlanes, kPending});
    std::vector<std::uint32_t> survivors;
    RefpointCullingJob::Scratch scratch;
    ActorFrameStatistics stats;
    PhaseLoop loop;
    loop.begin(stats, nullptr, nullptr);
    RefpointCullingJob{&s, &frustum, camera.eye(), candidates, &survivors, s.actorClass, &scratch}.run(loop);
    EXPECT_EQ(survivors, (std::vector<std::uint32_t>{0, 2}));
    EXPECT_EQ(candidates[0].stage, kInside);
    EXPECT_EQ(candidates[0].mask, 0);
    EXPECT_EQ(candidates[1].stage, kOutside);
    EXPECT_EQ(s.actorClass[1], ActorClass::A);
    EXPECT_EQ(s.actorClass[3], ActorClass::A);
    EXPECT_EQ(stats.a, 2u);
    EXPECT_EQ(stats.spheresTested, 4u);

    // No occlusion buffer: the occlusion job leaves the survivors as they are.
    RefpointOcclusionJob::Scratch cells;
    RefpointOcclusionJob{&s, nullptr, candidates, &survivors, s.actorClass, &cells}.run(loop);
    EXPECT_EQ(survivors, (std::vector<std::uint32_t>{0, 2}));
}

TEST(CascadeJobs, SkeletalLodListsTheShownAndGivesThePosedTheirNodes) {
    GroupedCrowd scene(5, 10.0, 5);
    const Crowd::State& s = scene.crowd.state();
    std::vector<Candidate> candidates;
    for (std::uint32_t m = 0; m < 5; ++m) candidates.push_back(Candidate{m, scene.group.get(), m, 0, kInside});
    const std::vector<std::uint32_t> survivors = {0, 1, 2, 3, 4};
    SurvivorDecisions decisions;
    decisions.outcome = {kPosed, kRejected, kImpostor, kPosed, kCached};
    decisions.detail2 = {4.0, 0.0, 1e6, 1e6, 1e6};  // actor 3 far: skeletal LOD drops nodes
    decisions.level = {0, 0, 0, 1, 1};
    PosedActors posed;
    ActorFrameStatistics stats;
    PhaseLoop loop;
    loop.begin(stats, nullptr, nullptr);
    SkeletalLodJob{&s, candidates, survivors, &decisions, true, &posed}.run(loop);
    const std::size_t nodes = s.tmpl[0]->nodeCount();
    EXPECT_EQ(posed.shown, (std::vector<std::uint32_t>{0, 2, 3, 4}));
    EXPECT_EQ(posed.posedOf, (std::vector<std::uint32_t>{0, PosedActors::kNotPosed, 1, PosedActors::kNotPosed}));
    EXPECT_EQ(posed.posed, (std::vector<std::uint32_t>{0, 3}));
    EXPECT_EQ(posed.level, (std::vector<int>{0, 1}));
    EXPECT_EQ(posed.nodeBase, (std::vector<std::uint32_t>{0, static_cast<std::uint32_t>(nodes)}));
    ASSERT_EQ(posed.active.size(), 2 * nodes);
    std::vector<std::uint8_t> expectedNear(nodes), expectedFar(nodes);
    computeActiveNodes(*s.tmpl[0], 4.0, expectedNear);
    computeActiveNodes(*s.tmpl[3], 1e6, expectedFar);
    EXPECT_TRUE(std::equal(expectedNear.begin(), expectedNear.end(), posed.active.begin()));
    EXPECT_TRUE(std::equal(expectedFar.begin(), expectedFar.end(), posed.active.begin() + long(nodes)));
    EXPECT_LT(std::count(expectedFar.begin(), expectedFar.end(), 1), std::count(expectedNear.begin(), expectedNear.end(), 1));

    // Skeletal LOD off: every node of every posed actor stays.
    SkeletalLodJob{&s, candidates, survivors, &decisions, false, &posed}.run(loop);
    EXPECT_EQ(std::count(posed.active.begin(), posed.active.end(), 1), static_cast<long>(2 * nodes));
}

TEST(CascadeJobs, AnImpostorDecisionWithoutAnImpostorDrawsNothing) {
    GroupedCrowd scene(1, 1.0, 9);
    const Crowd::State& s = scene.crowd.state();
    const Frustum frustum = streetCamera().frustum();
    const std::vector<Candidate> candidates = {Candidate{0, scene.group.get(), 0, 0, kInside}};
    const std::vector<std::uint32_t> survivors = {0};
    SurvivorDecisions decisions;
    decisions.outcome = {kImpostor};
    decisions.detail2 = {1e4};
    decisions.level = {0};
    PosedActors posed;
    posed.shown = {0};
    posed.posedOf = {PosedActors::kNotPosed};
    const InternalVisibility visibility;
    const std::vector<std::pair<const ActorTemplate*, std::shared_ptr<const Drawable>>> impostors;
    Settings settings;
    settings.impostors = &impostors;
    ActorFrameStatistics stats;
    DrawList list;
    PhaseLoop loop;
    loop.begin(stats, nullptr, &list);
    DrawListJob{&s, &frustum, 0.0, &settings, candidates, survivors, &decisions, &posed, &visibility}.run(loop);
    EXPECT_EQ(list.size(), 0u);
}
