// Skeletal and behavioural LOD: beyond a node's deactivation distance its DOFs are not evaluated
// (counted), its matrix is not built and its subtree is not traversed; behaviours declare
// distance-banded levels whose lower levels are cheaper; vaLod uses one distance per actor,
// scaled by priority.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "throng/testkit/Cameras.h"
#include "throng/testkit/ActorTestScenes.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"
#include "throng/scenegraph/OpCounter.h"

using namespace throng;
using namespace throng::testkit;

namespace {

struct OneActor {
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    ActorId id = 0;
};

std::unique_ptr<OneActor> standingActor(std::shared_ptr<const ActorTemplate> tmpl, std::shared_ptr<Behaviour> b,
                                        std::uint32_t slot, float priority = 1.0f) {
    auto s = std::make_unique<OneActor>();
    s->id = s->crowd.add(std::move(tmpl), std::move(b), slot, ActorLook{priority, glm::vec4(1), {}});
    s->root->addChild(s->crowd.makeActorNode(s->id));
    return s;
}

// One actor of `tmpl` playing its keyframes, alone in its scene.
std::unique_ptr<OneActor> keyframedActor(std::shared_ptr<const ActorTemplate> tmpl) {
    auto b = std::make_shared<KeyframeBehaviour>();
    KeyframeBehaviour::Actor a;
    a.tmpl = tmpl;
    return standingActor(tmpl, b, b->addActor(a));
}

Camera cameraAt(double distance) { return testkit::lookingAt(Vec3(0, 1, distance), Vec3(0, 1, 0), {0.8, 1.0, 0.1, 5000.0}); }

}  // namespace

TEST(SkeletalLod, BeyondItsDistanceANodeIsNotEvaluatedAndItsSubtreeNotTraversed) {
    const auto tmpl = makeTable3Template();  // the 20 distal nodes switch off beyond 50 m
    auto scene = keyframedActor(tmpl);
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
    auto scene = keyframedActor(tmpl);
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

// An oracle written apart from the production functions (no detailDistanceSquared, levelFor,
// computeActiveNodes or clip sampling): from where each Skeleton Root stands, the test works out
// the eye distance, the behavioural level of its own band list and the active nodes, then checks
// what the processor left in each actor's DOFs against the template's data alone: the rest pose
// beyond the last band, one of the clip's own key values where keys are held, values between keys
// where they are interpolated; and that exactly the active nodes were evaluated.
TEST(BehaviouralLod, LevelsAndActiveNodesMatchAnIndependentOracle) {
    const auto tmpl = makeSeedHumanoid();
    const std::vector<double> bands{20.0, 50.0};  // level 0 below 20 m, level 1 below 50 m, off beyond
    auto keyframes = std::make_shared<KeyframeBehaviour>(bands);
    Crowd crowd;
    auto root = std::make_shared<Group>();
    const int walk = tmpl->findClip("walk");
    std::vector<ActorId> ids;
    for (int i = 0; i < 40; ++i) {  // in a line straight ahead of the camera, 4 m to 82 m away
        KeyframeBehaviour::Actor a;
        a.tmpl = tmpl;
        a.clip = walk;
        a.position = Vec3(0.0, 0.0, -4.0 - 2.0 * i);
        ids.push_back(crowd.add(tmpl, keyframes, keyframes->addActor(a)));
        root->addChild(crowd.makeActorNode(ids.back()));
    }
    Camera camera;
    camera.setPerspective(1.0, 1.0, 0.1, 1000.0);
    camera.setLookAt(Vec3(0, 1, 0), Vec3(0, 1, -10), Vec3(0, 1, 0));
    ActorProcessor p(crowd);
    const AnimationClip& clip = *tmpl->clips()[std::size_t(walk)];
    const double time = 0.37;  // between keys of the walk clip
    const ActorFrameStatistics& s = p.processFrame(*root, camera, time);

    std::size_t expectedNodes = 0, seen[3] = {};
    for (ActorId id : ids) {
        // The eye distance, from the Skeleton Root's position.
        const Vec3 d = Vec3(crowd.skeletonRoot(id)[3]) - camera.eye();
        const double distance = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        const int level = distance < bands[0] ? 0 : distance < bands[1] ? 1 : 2;
        ++seen[level];
        // Active nodes: a node is on while nearer than its deactivation distance and its parent is on.
        std::vector<bool> active(tmpl->nodeCount());
        for (std::size_t i = 0; i < tmpl->nodeCount(); ++i) {
            const SkeletonNode& n = tmpl->nodes()[i];
            active[i] = distance < n.deactivationDistance && (n.parent < 0 || active[std::size_t(n.parent)]);
            expectedNodes += active[i];
        }
        const auto dofs = crowd.dofs(id);
        std::size_t between = 0;
        for (const ClipChannel& c : clip.channels()) {
            if (c.target != ClipChannel::Target::NodeDof || !active[c.node]) continue;
            const SkeletonNode& n = tmpl->nodes()[c.node];
            const auto width = std::size_t(dofValueCount(n.dofs[c.dof].kind));
            const std::uint32_t at = tmpl->dofValueOffset(c.node, c.dof);
            const std::span<const float> value = dofs.subspan(at, width);
            const std::span<const float> rest = tmpl->restDofs().subspan(at, width);
            const std::size_t stride = c.interpolation == Interpolation::CubicSpline ? 3 * width : width;
            const std::size_t valueOffset = c.interpolation == Interpolation::CubicSpline ? width : 0;
            bool isKey = false;
            for (std::size_t k = 0; k < c.times.size(); ++k)
                isKey = isKey || std::equal(value.begin(), value.end(), c.values.begin() + long(k * stride + valueOffset));
            if (level == 2) {
                EXPECT_TRUE(std::equal(value.begin(), value.end(), rest.begin())) << "actor " << id << " at " << distance << " m: rest pose";
            } else if (level == 1) {
                EXPECT_TRUE(isKey) << "actor " << id << " at " << distance << " m, node " << n.name << ": a held key";
            } else {
                between += !isKey;
            }
        }
        if (level == 0) {
            EXPECT_GT(between, 0u) << "actor " << id << " at " << distance << " m interpolates between keys";
        }
    }
    EXPECT_GT(seen[0], 3u);
    EXPECT_GT(seen[1], 3u);
    EXPECT_GT(seen[2], 3u);
    EXPECT_EQ(s.skeletonNodesEvaluated, expectedNodes);
    EXPECT_EQ(s.actorsPosed, ids.size());
}

// One eye distance per actor that passes CULL 2, however many LOD nodes it has; traditional
// processing computes one per LOD node instead.
TEST(SkeletalLod, OneEyeDistancePerActorThatPassesCull2) {
    auto scene = makeRandomCrowd(21, 800, 60.0);
    ActorProcessor p(scene->crowd);
    Camera camera;
    camera.setPerspective(1.0, 1.5, 0.1, 300.0);
    camera.setLookAt(Vec3(0, 20, 80), Vec3(0.0), Vec3(0, 1, 0));
    const ActorFrameStatistics& s = p.processFrame(*scene->root, camera, 1.0);
    std::uint64_t withDistance = 0;
    for (ActorId id : scene->ids) withDistance += std::isfinite(scene->crowd.eyeDistance(id));
    EXPECT_GT(s.eyeDistances, 100u);
    EXPECT_EQ(s.eyeDistances, s.b + s.c2 + s.c3_1 + s.c3_2) << "every actor past CULL 2, and no other";
    EXPECT_EQ(s.eyeDistances, withDistance);
    EXPECT_EQ(s.lodDistances, s.eyeDistances) << "no LOD node computes a distance of its own";
    p.setProcessing(Processing::Traditional);
    const ActorFrameStatistics& t = p.processFrame(*scene->root, camera, 1.0);
    EXPECT_EQ(t.eyeDistances, 0u);
    EXPECT_GT(t.lodDistances, 10 * s.eyeDistances) << "one per LOD node, for every actor inside the frustum";
}

// An LOD node's own distance scale (a town's tiles, LOD::setDistanceScale) multiplies on top of the
// processor's LOD scale and leaves the actors alone: a frame budget simplifies the town, or keeps
// it whole, whatever LOD the actors are at.
TEST(SceneLod, ANodesDistanceScaleMovesItsLevelsAndLeavesTheActorsAlone) {
    const auto tmpl = makeTable3Template();  // the 20 distal nodes switch off beyond 50 m
    auto scene = keyframedActor(tmpl);
    const auto nearMesh = std::make_shared<MeshDrawable>(makeBox("near", glm::vec3(0.0f), glm::vec3(1.0f), glm::vec4(1.0f)));
    const auto farMesh = std::make_shared<MeshDrawable>(makeBox("far", glm::vec3(0.0f), glm::vec3(1.0f), glm::vec4(1.0f)));
    auto tile = std::make_shared<LOD>();
    tile->addChild(std::make_shared<Geometry>(nearMesh), 30.0);
    tile->addChild(std::make_shared<Geometry>(farMesh), 10000.0);
    scene->root->addChild(tile);
    ActorProcessor p(scene->crowd);
    const auto tileShows = [&] {
        for (const DrawItem& item : p.drawList().items())
            if (item.actor == kNoActor) return item.drawable == nearMesh.get() ? std::string("near") : std::string("far");
        return std::string("nothing");
    };
    // 20 m away at LOD scale 3: the actor's distal nodes off (60 m > 50 m), the tile at its far level.
    p.setLodScale(3.0);
    EXPECT_EQ(p.processFrame(*scene->root, cameraAt(20.0), 0.25).skeletonNodesEvaluated, 20u);
    EXPECT_EQ(tileShows(), "far");
    // The node's scale 0.01: the tile near again (0.6 m), the actor as before.
    tile->setDistanceScale(0.01);
    EXPECT_EQ(p.processFrame(*scene->root, cameraAt(20.0), 0.5).skeletonNodesEvaluated, 20u);
    EXPECT_EQ(tileShows(), "near");
    // And the reverse: the actors whole, the tile simplified (20 m x 1 x 2 = 40 m).
    p.setLodScale(1.0);
    tile->setDistanceScale(2.0);
    EXPECT_EQ(p.processFrame(*scene->root, cameraAt(20.0), 0.75).skeletonNodesEvaluated, 40u);
    EXPECT_EQ(tileShows(), "far");
    tile->setDistanceScale(1.0);
    p.processFrame(*scene->root, cameraAt(20.0), 1.0);
    EXPECT_EQ(tileShows(), "near");
    for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
        EXPECT_THROW(tile->setDistanceScale(bad), std::invalid_argument) << bad;
}
