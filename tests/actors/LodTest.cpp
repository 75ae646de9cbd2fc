// Skeletal and behavioural LOD: beyond a node's deactivation distance its DOFs are not evaluated
// (counted), its matrix is not built and its subtree is not traversed; behaviours declare
// distance-banded levels whose lower levels are cheaper; vaLod uses one distance per actor,
// scaled by priority.

#include <gtest/gtest.h>

#include <cmath>

#include "ActorTestScenes.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/OpCounter.h"

using namespace throng;
using namespace throng::testing;

namespace {

struct OneActor {
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    ActorId id = 0;
};

std::unique_ptr<OneActor> standingActor(std::shared_ptr<const ActorTemplate> tmpl, std::shared_ptr<Behaviour> b,
                                        std::uint32_t slot, float priority = 1.0f) {
    auto s = std::make_unique<OneActor>();
    s->id = s->crowd.add(std::move(tmpl), std::move(b), slot, ActorLook{priority, glm::vec4(1)});
    s->root->addChild(s->crowd.makeActorNode(s->id));
    return s;
}

Camera cameraAt(double distance) {
    Camera c;
    c.setPerspective(0.8, 1.0, 0.1, 5000.0);
    c.setLookAt(Vec3(0, 1, distance), Vec3(0, 1, 0), Vec3(0, 1, 0));
    return c;
}

}  // namespace

TEST(SkeletalLod, BeyondItsDistanceANodeIsNotEvaluatedAndItsSubtreeNotTraversed) {
    const auto tmpl = makeTable3Template();  // the 20 distal nodes switch off beyond 50 m
    auto b = std::make_shared<KeyframeBehaviour>();
    KeyframeBehaviour::Actor a;
    a.tmpl = tmpl;
    auto scene = standingActor(tmpl, b, b->addActor(a));
    ActorProcessor p(scene->crowd);
    p.counter().setEnabled(true);

    const ActorFrameStatistics near = p.processFrame(*scene->root, cameraAt(20.0), 0.25);
    EXPECT_EQ(near.skeletonNodesEvaluated, 40u);
    EXPECT_EQ(p.counter().operations(OpCategory::SkeletonMatrix), 40u);

    // Poison the DOFs: values of deactivated nodes must stay untouched by the behaviour.
    auto& dofs = scene->crowd.state().dofs;
    std::fill(dofs.begin(), dofs.end(), -77.0f);
    const ActorFrameStatistics far = p.processFrame(*scene->root, cameraAt(120.0), 0.75);
    EXPECT_EQ(far.skeletonNodesEvaluated, 20u);
    EXPECT_EQ(p.counter().operations(OpCategory::SkeletonMatrix), 20u);
    std::size_t untouched = 0, written = 0;
    for (std::size_t i = 0; i < tmpl->nodeCount(); ++i) {
        const bool off = tmpl->nodes()[i].deactivationDistance < 120.0;
        const float v = dofs[tmpl->dofOffset(i)];
        if (off) {
            EXPECT_EQ(v, -77.0f) << "deactivated node " << tmpl->nodes()[i].name << " was evaluated";
            ++untouched;
        } else {
            EXPECT_NE(v, -77.0f) << "active node " << tmpl->nodes()[i].name << " was not evaluated";
            ++written;
        }
    }
    EXPECT_EQ(untouched, 20u);
    EXPECT_EQ(written, 20u);
    // And no draw item comes from a deactivated node.
    for (const DrawItem& item : p.drawList().items())
        if (item.part < tmpl->nodeCount()) {
            EXPECT_GE(tmpl->nodes()[item.part].deactivationDistance, 120.0);
        }
}

TEST(SkeletalLod, PriorityScalesTheDistances) {
    const auto tmpl = makeSeedHumanoid();
    auto b = std::make_shared<KeyframeBehaviour>();
    KeyframeBehaviour::Actor a;
    a.tmpl = tmpl;
    auto normal = standingActor(tmpl, b, b->addActor(a), 1.0f);
    auto important = standingActor(tmpl, b, b->addActor(a), 4.0f);
    ActorProcessor pn(normal->crowd), pi(important->crowd);
    // At 60 m the humanoid has lost head and neck (30 m); priority 4 keeps them (60 / 4 = 15 m).
    const auto sn = pn.processFrame(*normal->root, cameraAt(60.0), 0.0);
    const auto si = pi.processFrame(*important->root, cameraAt(60.0), 0.0);
    EXPECT_EQ(sn.skeletonNodesEvaluated, 10u);
    EXPECT_EQ(si.skeletonNodesEvaluated, 12u);
    EXPECT_GT(si.primitives, sn.primitives);
    // The LOD scale works the other way.
    pn.setLodScale(0.1);
    EXPECT_EQ(pn.processFrame(*normal->root, cameraAt(60.0), 0.0).skeletonNodesEvaluated, 13u);
    EXPECT_THROW(pn.setLodScale(0.0), std::invalid_argument);
}

TEST(SkeletalLod, FarActorsProcessNoSkeletonNodeAtAll) {
    const auto tmpl = makeSeedHumanoid();
    auto b = std::make_shared<KeyframeBehaviour>();
    KeyframeBehaviour::Actor a;
    a.tmpl = tmpl;
    auto scene = standingActor(tmpl, b, b->addActor(a));
    ActorProcessor p(scene->crowd);
    const auto s = p.processFrame(*scene->root, cameraAt(400.0), 0.0);
    EXPECT_EQ(s.skeletonNodesEvaluated, 0u);
    ASSERT_EQ(p.drawList().size(), 1u);
    EXPECT_EQ(p.drawList().items()[0].part, tmpl->nodeCount()) << "the actor-level piece";
}

TEST(BehaviouralLod, LevelsAreChosenByDistanceAndLowerLevelsAreCheaper) {
    const auto tmpl = makeSeedHumanoid();
    auto gait = std::make_shared<ProceduralGait>(std::vector<double>{15.0, 1e9});
    ProceduralGait::Actor a;
    a.radius = 0.0;
    auto scene = standingActor(tmpl, gait, gait->addActor(a));
    EXPECT_EQ(gait->levelFor(10.0), 0);
    EXPECT_EQ(gait->levelFor(20.0), 1);
    EXPECT_EQ(gait->levelFor(2e9), 2) << "beyond the last band the behaviour is off";
    ActorProcessor p(scene->crowd);
    p.counter().setEnabled(true);
    // Both distances keep all 12 body nodes but the eyes (10 m): compare the behaviour's cost per node.
    p.processFrame(*scene->root, cameraAt(12.0), 0.4);
    const std::uint64_t precise = p.counter().fmult(OpCategory::SkeletonDofValues);
    const std::uint64_t nodesPrecise = p.counter().operations(OpCategory::SkeletonMatrix);
    p.processFrame(*scene->root, cameraAt(25.0), 0.4);
    const std::uint64_t cheap = p.counter().fmult(OpCategory::SkeletonDofValues);
    const std::uint64_t nodesCheap = p.counter().operations(OpCategory::SkeletonMatrix);
    ASSERT_EQ(nodesPrecise, nodesCheap);
    EXPECT_LT(cheap, precise) << "level 1 must cost less than level 0";
    // With behavioural LOD off, level 0 everywhere.
    p.setBehaviouralLod(false);
    p.processFrame(*scene->root, cameraAt(25.0), 0.4);
    EXPECT_EQ(p.counter().fmult(OpCategory::SkeletonDofValues), precise);
}

TEST(BehaviouralLod, HoldingKeysIsCheaperAndStillAKeyPose) {
    const auto tmpl = makeSeedHumanoid();
    auto keyframes = std::make_shared<KeyframeBehaviour>(std::vector<double>{15.0, 1e9});
    KeyframeBehaviour::Actor a;
    a.tmpl = tmpl;
    const std::uint32_t slot = keyframes->addActor(a);
    std::vector<float> interpolated(tmpl->restDofs().begin(), tmpl->restDofs().end()), held = interpolated;
    OpTally ops0, ops1;
    keyframes->pose(slot, 0.1, 0, *tmpl, {}, interpolated, &ops0);
    keyframes->pose(slot, 0.1, 1, *tmpl, {}, held, &ops1);
    EXPECT_LT(ops1.fmult(), ops0.fmult());
    std::vector<float> atKey(tmpl->restDofs().begin(), tmpl->restDofs().end());
    keyframes->pose(slot, 0.0, 0, *tmpl, {}, atKey, nullptr);
    EXPECT_EQ(held, atKey) << "0.1 s holds the key at 0 s";
    EXPECT_NE(interpolated, atKey);
}
