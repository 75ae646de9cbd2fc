// Numerical hard cases for actors (DESIGN.md): actors 10^6 m from the origin culled and placed to the
// millimetre, a million frames of closed-form animation keeping bone lengths and orthonormal
// frames (state that integrates step by step has its own million-step test in tests/sim), clips
// looping at t = 10^6 s, and the camera inside a Refpoint Bsphere.

#include <gtest/gtest.h>

#include <cmath>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/research/CostModelScene.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/Camera.h"

using namespace throng;
using namespace throng::testkit;

TEST(ActorStability, TheTable2SceneAMillionMetresAwayClassifiesAndDrawsAsTraditionalProcessing) {
    // The same scene at the origin, as the reference for where things are drawn.
    const auto table3 = makeTable3Template();
    Crowd nearCrowd;
    CostModelSceneOptions nearOptions;
    nearOptions.group = true;
    const CostModelScene nearScene = buildCostModelScene(nearCrowd, table3, std::make_shared<KeyframeBehaviour>(), nearOptions);
    ActorProcessor nearProcessor(nearCrowd);
    nearProcessor.processFrame(*nearScene.root, nearScene.camera, nearScene.time);
    const auto listed = nearProcessor.drawList().items();
    const std::vector<DrawItem> nearItems(listed.begin(), listed.end());
    for (const Vec3 origin : {Vec3(1e6, 0, -1e6), Vec3(-3e6, 2e5, 7e6)}) {
        Crowd crowd;
        CostModelSceneOptions options;
        options.origin = origin;
        options.group = true;
        const CostModelScene scene = buildCostModelScene(crowd, table3, std::make_shared<KeyframeBehaviour>(), options);
        ActorProcessor p(crowd);
        const ActorFrameStatistics& s = p.processFrame(*scene.root, scene.camera, scene.time);
        EXPECT_EQ(classCounts(s), "20 30 20 20 8 2");
        const auto actor = primitives(p.drawList());
        EXPECT_GT(actor.size(), 500u);
        // The matrices drawn put every part where it is drawn at the origin, shifted by `origin`, to
        // the millimetre (double precision world matrices: 10^6 m leaves about 10^-10 m of rounding).
        const auto& items = p.drawList().items();
        ASSERT_EQ(items.size(), nearItems.size());
        double worst = 0.0;
        for (std::size_t i = 0; i < items.size(); ++i) {
            ASSERT_EQ(items[i].drawable, nearItems[i].drawable) << "item " << i;
            ASSERT_EQ(items[i].part, nearItems[i].part) << "item " << i;
            const Mat4 far = items[i].world.toMat4();
            const Mat4 near = nearItems[i].world.toMat4();
            worst = std::max(worst, glm::length(Vec3(far[3]) - origin - Vec3(near[3])));
            for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(Vec3(far[c]) - Vec3(near[c])), 1e-9) << "item " << i;
        }
        EXPECT_LT(worst, 1e-3) << "metres between where a part is drawn far away and where it is drawn at the origin";
        p.setProcessing(Processing::Traditional);
        p.processFrame(*scene.root, scene.camera, scene.time);
        EXPECT_TRUE(primitives(p.drawList()) == actor);
    }
}

TEST(ActorStability, AMillionFramesOfAnimationWithoutDrift) {
    // A walking key-framed humanoid on a circle and a procedurally walking Table 3 actor, a million
    // frames at 60 Hz: bone lengths must stay within 1e-5 of the template's, and the Reference
    // Point's rotation orthonormal. Both behaviours are closed-form in time (nothing accumulates),
    // so this checks evaluation at large times; LongRun.* checks state integrated step by step.
    Crowd crowd;
    const auto humanoid = makeSeedHumanoid();
    const auto table3 = makeTable3Template();
    auto keyframes = std::make_shared<KeyframeBehaviour>();
    KeyframeBehaviour::Actor k;
    k.tmpl = humanoid;
    k.pathRadius = 5.0;
    k.pathSpeed = 1.4;
    auto gait = std::make_shared<ProceduralGait>();
    ProceduralGait::Actor g;
    g.radius = 8.0;
    auto root = std::make_shared<Group>();
    const ActorId ids[2] = {crowd.add(humanoid, keyframes, keyframes->addActor(k)), crowd.add(table3, gait, gait->addActor(g))};
    for (ActorId id : ids) root->addChild(crowd.makeActorNode(id));
    Camera camera;
    camera.setPerspective(1.2, 1.5, 0.1, 100.0);
    camera.setLookAt(Vec3(0, 5, 20), Vec3(0.0), Vec3(0, 1, 0));
    ActorProcessor p(crowd);
    constexpr std::uint64_t kFrames = 1'000'000;
    double worstBone = 0.0, worstOrtho = 0.0;
    for (std::uint64_t f = 0; f <= kFrames; ++f) {
        const double t = double(f) / 60.0;
        p.processFrame(*root, camera, t);
        if (f % 50'000 != 0) continue;
        for (ActorId id : ids) {
            const ActorTemplate& tmpl = crowd.templateOf(id);
            std::vector<Affine> model(tmpl.nodeCount());
            computeModelTransforms(tmpl, crowd.dofs(id), {}, model);
            for (std::size_t i = 0; i < tmpl.nodeCount(); ++i) {
                const int parent = tmpl.nodes()[i].parent;
                if (parent < 0) continue;
                const double expected = glm::length(glm::dvec3(tmpl.nodes()[i].restTranslation));
                const double got = glm::length(glm::dvec3(model[i].translation - model[std::size_t(parent)].translation));
                worstBone = std::max(worstBone, std::abs(got - expected) / expected);
            }
            const glm::dmat3 r(crowd.referencePoint(id));
            worstOrtho = std::max(worstOrtho, double(glm::length(glm::dvec3(1) - glm::dvec3(glm::length(r[0]), glm::length(r[1]), glm::length(r[2])))));
        }
    }
    EXPECT_LT(worstBone, 1e-5);
    EXPECT_LT(worstOrtho, 1e-12);
    RecordProperty("worstBoneLengthError", std::to_string(worstBone));
}

TEST(ActorStability, ClipsLoopAtAMillionSeconds) {
    const auto humanoid = makeSeedHumanoid();
    const AnimationClip& walk = *humanoid->clips()[static_cast<std::size_t>(humanoid->findClip("walk"))];
    std::vector<float> early(humanoid->restDofs().begin(), humanoid->restDofs().end()), late = early;
    // 10^6 s is a whole number of 2 s cycles: the pose must be the one at 0.3 s, to float precision.
    walk.sample(*humanoid, 0.3, true, {}, early);
    walk.sample(*humanoid, 1e6 + 0.3, true, {}, late);
    for (std::size_t i = 0; i < early.size(); ++i) EXPECT_NEAR(early[i], late[i], 1e-5);
    EXPECT_NEAR(walk.localTime(1e6 + 0.3, true), 0.3, 1e-9);
}

TEST(ActorStability, CameraInsideARefpointSphere) {
    auto scene = makeRandomCrowd(8, 400, 40.0);
    ActorProcessor p(scene->crowd);
    p.setBehaviouralLod(false);
    Camera outside;
    outside.setPerspective(1.0, 1.5, 0.1, 200.0);
    outside.setLookAt(Vec3(0, 50, 100), Vec3(0.0), Vec3(0, 1, 0));
    p.processFrame(*scene->root, outside, 1.0);  // places the actors
    for (int k = 0; k < 20; ++k) {
        const ActorId id = scene->ids[std::size_t(k * 13) % scene->ids.size()];
        const Vec3 centre = scene->crowd.refpointSphere(id).center();
        Camera inside;
        inside.setPerspective(1.0, 1.5, 0.05, 200.0);
        inside.setLookAt(centre, centre + Vec3(std::cos(k), 0.1, std::sin(k)), Vec3(0, 1, 0));
        p.setProcessing(Processing::Actor);
        p.processFrame(*scene->root, inside, 1.0);
        if (scene->crowd.actorClass(id) != ActorClass::CulledWithGroup) {
            EXPECT_NE(scene->crowd.actorClass(id), ActorClass::A) << "an eye inside a Refpoint Bsphere sees into it";
        }
        const auto actor = primitives(p.drawList());
        p.setProcessing(Processing::Traditional);
        p.processFrame(*scene->root, inside, 1.0);
        EXPECT_TRUE(primitives(p.drawList()) == actor) << "camera " << k;
    }
}
