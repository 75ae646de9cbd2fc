// The culling cascade against traditional processing: the same primitives on random scenes with
// random cameras (cameras inside spheres among them), view-independent Reference Points, the Table 2
// classification, actors culled with a generic group, and held objects.

#include <atomic>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <random>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/research/CostModelScene.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"
#include "throng/scenegraph/Occluder.h"
#include "throng/scenegraph/OcclusionBuffer.h"
#include "throng/scenegraph/TraditionalProcessor.h"

using namespace throng;
using namespace throng::testkit;

namespace {

Camera randomCamera(std::mt19937_64& rng, double extent) {
    std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
    Camera c;
    c.setPerspective(0.3 + 1.5 * unit(rng), 0.7 + unit(rng), 0.05 + unit(rng), 50.0 + 400.0 * unit(rng));
    const Vec3 eye(extent * u(rng), 1.0 + 10.0 * unit(rng), extent * u(rng));
    Vec3 target(extent * u(rng), 0.0, extent * u(rng));
    if (glm::length(target - eye) < 1.0) target += Vec3(5, 0, 0);
    c.setLookAt(eye, target, Vec3(0, 1, 0));
    return c;
}

// A camera standing at an actor's Reference Point or Skeleton Root, looking anywhere.
Camera cameraInsideActor(std::mt19937_64& rng, const Vec3& at) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Camera c;
    c.setPerspective(1.2, 1.5, 0.05, 200.0);
    c.setLookAt(at, at + Vec3(u(rng), 0.3 * u(rng), u(rng)) + Vec3(1e-3, 0, 0), Vec3(0, 1, 0));
    return c;
}

}  // namespace

TEST(Cascade, DrawsExactlyWhatTraditionalProcessingDrawsOnRandomScenes) {
    std::size_t frames = 0, drawn = 0, rejected = 0, insideCameras = 0;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        auto scene = makeRandomCrowd(seed, 1200, 120.0);
        ActorProcessor processor(scene->crowd);
        processor.setBehaviouralLod(false);  // both methods then pose actors identically
        std::mt19937_64 rng(seed * 77);
        for (int f = 0; f < 12; ++f) {
            const double time = 0.37 * f;
            TransformDofs vehicle;
            vehicle.translation = Vec3(30.0 * std::sin(time), 0.0, 20.0 * f - 100.0);
            scene->vehicle->setDofs(vehicle);
            Camera camera = randomCamera(rng, 120.0);
            if (f % 3 == 2) {  // stand inside an actor's spheres: its Reference Point or Skeleton Root
                const ActorId id = scene->ids[rng() % scene->ids.size()];
                processor.setProcessing(Processing::Traditional);
                processor.processFrame(*scene->root, camera, time);  // places every actor at `time`
                camera = cameraInsideActor(rng, f % 2 ? Vec3(scene->crowd.referencePoint(id)[3])
                                                      : Vec3(scene->crowd.skeletonRoot(id)[3]));
                ++insideCameras;
            }
            processor.setProcessing(Processing::Traditional);
            processor.processFrame(*scene->root, camera, time);
            const auto expected = primitives(processor.drawList());
            processor.setProcessing(Processing::Actor);
            const ActorFrameStatistics& s = processor.processFrame(*scene->root, camera, time);
            const auto got = primitives(processor.drawList());
            ASSERT_EQ(got.size(), expected.size()) << "seed " << seed << " frame " << f;
            ASSERT_TRUE(got == expected) << "seed " << seed << " frame " << f;
            ++frames;
            drawn += got.size();
            rejected += s.a + s.c1;
        }
    }
    EXPECT_EQ(insideCameras, 12u);
    EXPECT_GT(drawn, 5000u) << "the cameras must see actors";
    EXPECT_GT(rejected, 5000u) << "the cascade must reject actors";
}

TEST(Cascade, WithBehaviouralLodEveryPartDrawnIsVisibleInItsOwnPose) {
    // With behavioural LOD the poses differ from traditional processing's, so check actor
    // processing against a brute-force test of the poses it produced: a part is drawn exactly when
    // its own sphere is not outside the frustum.
    auto scene = makeRandomCrowd(11, 1000, 80.0);
    ActorProcessor processor(scene->crowd);
    std::mt19937_64 rng(5);
    const Crowd::State& s = scene->crowd.state();
    std::size_t checked = 0;
    for (int f = 0; f < 6; ++f) {
        const Camera camera = randomCamera(rng, 80.0);
        processor.processFrame(*scene->root, camera, 0.5 * f);
        const Frustum frustum = camera.frustum();
        std::vector<PrimitiveKey> expected;
        for (ActorId id = 0; id < scene->crowd.size(); ++id) {
            const ActorClass c = scene->crowd.actorClass(id);
            if (c == ActorClass::A || c == ActorClass::C1 || c == ActorClass::NotInScene || c == ActorClass::CulledWithGroup) continue;
            const ActorTemplate& t = *s.tmpl[id];
            const double d2 = detailDistanceSquared(s.sklsWorld[id], camera.eye(), 1.0, s.priority[id]);
            std::vector<std::uint8_t> active(t.nodeCount());
            computeActiveNodes(t, d2, active);
            std::vector<Affine> model(t.nodeCount());
            computeModelTransforms(t, scene->crowd.dofs(id), active, model);
            const std::uint32_t member = s.member[id];
            const int rootLevel = t.rootGeometry().selectSquared(d2);
            if (rootLevel >= 0)
                if (const auto& d = t.rootGeometry().levels()[std::size_t(rootLevel)].drawable)
                    if (frustum.classify(d->localBound().transformed(s.sklsWorld[id])) != Containment::Outside)
                        expected.emplace_back(s.owner[id], member, std::uint32_t(t.nodeCount()), d.get());
            for (std::size_t i = 0; i < t.nodeCount(); ++i) {
                if (!active[i]) continue;
                const int level = t.nodes()[i].geometry.selectSquared(d2);
                if (level < 0) continue;
                const auto& d = t.nodes()[i].geometry.levels()[std::size_t(level)].drawable;
                if (d && frustum.classify(partWorldSphere(d->localBound(), model[i], s.sklsWorld[id])) != Containment::Outside)
                    expected.emplace_back(s.owner[id], member, std::uint32_t(i), d.get());
            }
        }
        std::sort(expected.begin(), expected.end());
        ASSERT_TRUE(primitives(processor.drawList()) == expected) << "frame " << f;
        checked += expected.size();
    }
    EXPECT_GT(checked, 1000u);
}

TEST(Cascade, ReferencePointsDoNotDependOnTheCamera) {
    // Three identical crowds, three cameras: at the crowd, away from it, and moving. The Reference
    // Point trajectories must be bitwise identical, in both methods.
    auto trajectories = [](int cameraKind, Processing processing) {
        auto scene = makeRandomCrowd(21, 300, 60.0);
        ActorProcessor p(scene->crowd);
        p.setProcessing(processing);
        std::vector<Mat4> out;
        for (int f = 0; f < 40; ++f) {
            Camera c;
            c.setPerspective(1.0, 1.5, 0.1, 500);
            if (cameraKind == 0) c.setLookAt(Vec3(0, 30, 150), Vec3(0.0));
            if (cameraKind == 1) c.setLookAt(Vec3(0, 30, 150), Vec3(0, 30, 300));
            if (cameraKind == 2) c.setLookAt(Vec3(100.0 * std::cos(0.2 * f), 20, 100.0 * std::sin(0.2 * f)), Vec3(0.0));
            p.processFrame(*scene->root, c, f / 30.0);
            for (ActorId id = 0; id < scene->crowd.size(); ++id) out.push_back(scene->crowd.referencePoint(id));
        }
        return out;
    };
    const auto looking = trajectories(0, Processing::Actor);
    const auto away = trajectories(1, Processing::Actor);
    const auto moving = trajectories(2, Processing::Actor);
    const auto traditional = trajectories(1, Processing::Traditional);
    ASSERT_EQ(looking.size(), away.size());
    EXPECT_EQ(0, std::memcmp(looking.data(), away.data(), looking.size() * sizeof(Mat4)));
    EXPECT_EQ(0, std::memcmp(looking.data(), moving.data(), looking.size() * sizeof(Mat4)));
    EXPECT_EQ(0, std::memcmp(looking.data(), traditional.data(), looking.size() * sizeof(Mat4)));
}

class Table2 : public ::testing::TestWithParam<bool> {};

TEST_P(Table2, TheExampleSceneGivesExactlyTheTable2CountsInThePipelineStatistics) {
    Crowd crowd;
    CostModelSceneOptions options;
    options.group = GetParam();
    const CostModelScene scene =
        buildCostModelScene(crowd, makeTable3Template(), std::make_shared<KeyframeBehaviour>(), options);
    ActorProcessor processor(crowd);
    const ActorFrameStatistics& s = processor.processFrame(*scene.root, scene.camera, scene.time);
    EXPECT_EQ(s.actorsInScene, 100u);
    EXPECT_EQ(classCounts(s), "20 30 20 20 8 2");
    EXPECT_EQ(s.culledWithGroup, 0u);
    // Skeletal LOD halves the Skeleton nodes of the 60 posed actors (fLODtopo = 0.5).
    EXPECT_EQ(s.actorsPosed, 60u);
    EXPECT_EQ(s.skeletonNodesEvaluated, 60u * 20u);
    // Each actor is in the class it was placed for.
    const ActorClass classes[6] = {ActorClass::A, ActorClass::B, ActorClass::C1, ActorClass::C2, ActorClass::C3_1, ActorClass::C3_2};
    for (std::size_t c = 0; c < 6; ++c)
        for (ActorId id : scene.byClass[c]) EXPECT_EQ(crowd.actorClass(id), classes[c]) << "actor " << id;
    // And traditional processing draws the same primitives.
    const auto actorPrimitives = primitives(processor.drawList());
    processor.setProcessing(Processing::Traditional);
    processor.processFrame(*scene.root, scene.camera, scene.time);
    EXPECT_TRUE(primitives(processor.drawList()) == actorPrimitives);
}

INSTANTIATE_TEST_SUITE_P(ActorNodesAndGroupNode, Table2, ::testing::Bool());

TEST(Cascade, ScaledTable2ProportionsHoldForLargerScenes) {
    const CascadeCounts counts = CascadeCounts::scaled(1000);
    EXPECT_EQ(counts.total(), 1000u);
    EXPECT_EQ(counts.a, 200u);
    EXPECT_EQ(counts.c3_2, 20u);
    Crowd crowd;
    CostModelSceneOptions options;
    options.counts = counts;
    options.group = true;
    const CostModelScene scene = buildCostModelScene(crowd, makeTable3Template(), std::make_shared<KeyframeBehaviour>(), options);
    ActorProcessor processor(crowd);
    const ActorFrameStatistics& s = processor.processFrame(*scene.root, scene.camera, scene.time);
    EXPECT_EQ(classCounts(s), "200 300 200 200 80 20");
}

TEST(Cascade, ActorsBelowAGenericGroupAreCulledWithItFirst) {
    auto scene = makeRandomCrowd(3, 200, 30.0);
    // Park the vehicle far behind the camera: its actors are never reached.
    TransformDofs far;
    far.translation = Vec3(0, 0, 5000);
    scene->vehicle->setDofs(far);
    std::size_t onVehicle = 0;
    for (ActorId id : scene->ids) onVehicle += scene->crowd.state().owner[id]->parent() == scene->vehicle.get();
    ASSERT_GT(onVehicle, 5u);
    Camera camera;
    camera.setPerspective(1.0, 1.5, 0.1, 300.0);
    camera.setLookAt(Vec3(0, 10, 60), Vec3(0.0), Vec3(0, 1, 0));
    ActorProcessor processor(scene->crowd);
    const ActorFrameStatistics& s = processor.processFrame(*scene->root, camera, 0.0);
    EXPECT_EQ(s.culledWithGroup, onVehicle);
    for (ActorId id : scene->ids)
        if (scene->crowd.state().owner[id]->parent() == scene->vehicle.get()) {
            EXPECT_EQ(scene->crowd.actorClass(id), ActorClass::CulledWithGroup);
            // Their Reference Points still follow the vehicle (simulation state is always computed).
            EXPECT_GT(scene->crowd.referencePoint(id)[3].z, 4000.0);
        }
    EXPECT_EQ(s.actorsInScene, s.culledWithGroup + s.a + s.b + s.c1 + s.c2 + s.c3_1 + s.c3_2);
}

// A wall across the middle of a random crowd: with occlusion the actors behind it leave the cascade
// as Occluded (their class and the counters say at which stage), everything drawn is drawn without
// occlusion too, nothing is hidden that the buffer does not hide, and threads change nothing.
TEST(Cascade, OcclusionRejectsOnlyWhatTheBufferHidesWhateverTheThreads) {
    auto scene = makeRandomCrowd(11, 1500, 60.0);
    auto wall = std::make_shared<Transform>();
    wall->setMatrix(glm::translate(Mat4(1.0), Vec3(0, 0, 0)));
    wall->addChild(std::make_shared<Occluder>(std::vector<AxisBox>{AxisBox{glm::vec3(-70, -20, -1), glm::vec3(70, 20, 1)}},
                                              AxisBox{glm::vec3(-71, -21, -2), glm::vec3(71, 21, 2)}));
    scene->root->addChild(wall);
    Camera camera;
    camera.setPerspective(1.0, 1.6, 0.1, 500.0);
    camera.setLookAt(Vec3(0, 5, 90), Vec3(0, 0, 0), Vec3(0, 1, 0));

    ActorProcessor plain(scene->crowd);
    const ActorFrameStatistics off = plain.processFrame(*scene->root, camera, 0.0);
    EXPECT_EQ(off.occlusionTests, 0u);
    EXPECT_EQ(off.occludersDrawn, 0u);
    std::vector<std::pair<ActorId, std::uint32_t>> drawnOff;
    for (const DrawItem& item : plain.drawList().items()) drawnOff.emplace_back(item.actor, item.part);

    std::vector<ActorClass> classes[2];
    std::vector<std::pair<ActorId, std::uint32_t>> drawn[2];
    for (unsigned threads : {1u, 2u}) {
        ActorProcessor occluding(scene->crowd);
        occluding.setThreads(threads);
        occluding.setOcclusion(OcclusionSettings{});
        const ActorFrameStatistics s = occluding.processFrame(*scene->root, camera, 0.0);
        EXPECT_EQ(s.occludersDrawn, 1u);
        const std::uint64_t hidden = s.occludedWithGroup + s.occludedRefpoint + s.occludedSklsroot;
        EXPECT_GT(hidden, 200u);
        EXPECT_EQ(s.actorsInScene, s.culledWithGroup + s.a + s.b + s.c1 + s.c2 + s.c3_1 + s.c3_2 + hidden);
        const OcclusionBuffer& buffer = occluding.occlusion()->buffer();
        std::uint64_t occluded = 0;
        for (ActorId id : scene->ids) {
            classes[threads - 1].push_back(scene->crowd.actorClass(id));
            if (scene->crowd.actorClass(id) != ActorClass::Occluded) continue;
            ++occluded;
            EXPECT_TRUE(buffer.occluded(scene->crowd.state().refSphereWorld[id]) ||
                        buffer.occluded(BoundingSphere(Vec3(scene->crowd.state().sklsWorld[id][3]), scene->crowd.state().sklsRadius[id])))
                << "actor " << id << " was rejected but neither of its spheres is hidden";
            EXPECT_LT(scene->crowd.state().refSphereWorld[id].center().z, 1.0) << "actor " << id << " is in front of the wall";
        }
        EXPECT_EQ(occluded, s.occludedRefpoint + s.occludedSklsroot + s.occludedWithGroup);
        for (const DrawItem& item : occluding.drawList().items()) {
            drawn[threads - 1].emplace_back(item.actor, item.part);
            EXPECT_NE(std::find(drawnOff.begin(), drawnOff.end(), std::make_pair(item.actor, item.part)), drawnOff.end());
        }
    }
    EXPECT_EQ(classes[0], classes[1]);
    EXPECT_EQ(drawn[0], drawn[1]);
}

// Occlusion's cells are squares fixed in the world: survivors spread over more than 3 km (two far
// actors high at the sides of the view) are binned by a hash of their squares instead of in order over
// their window, and the crowd near the wall forms the same cells, hides the same actors.
TEST(Cascade, OcclusionCellsAreTheSameWhenTheSurvivorsSpreadTooWideToBinInOrder) {
    const auto build = [](bool far) {
        auto scene = makeRandomCrowd(11, 1500, 60.0);
        auto wall = std::make_shared<Transform>();
        wall->addChild(std::make_shared<Occluder>(std::vector<AxisBox>{AxisBox{glm::vec3(-70, -20, -1), glm::vec3(70, 20, 1)}},
                                                  AxisBox{glm::vec3(-71, -21, -2), glm::vec3(71, 21, 2)}));
        scene->root->addChild(wall);
        if (far) {
            static const auto humanoid = makeSeedHumanoid();
            auto keyframes = std::make_shared<KeyframeBehaviour>(std::vector<double>{30.0, 1e9});
            for (double x : {-3000.0, 3000.0}) {
                KeyframeBehaviour::Actor a;
                a.tmpl = humanoid;
                a.position = Vec3(x, 2000.0, -5000.0);  // seen above the wall
                scene->root->addChild(scene->crowd.makeActorNode(scene->crowd.add(humanoid, keyframes, keyframes->addActor(a))));
            }
        }
        return scene;
    };
    Camera camera;
    camera.setPerspective(1.0, 1.6, 0.1, 10000.0);
    camera.setLookAt(Vec3(0, 5, 90), Vec3(0, 0, 0), Vec3(0, 1, 0));
    auto near = build(false), wide = build(true);
    ActorProcessor inOrder(near->crowd), hashed(wide->crowd);
    inOrder.setOcclusion(OcclusionSettings{});
    hashed.setOcclusion(OcclusionSettings{});
    const ActorFrameStatistics a = inOrder.processFrame(*near->root, camera, 0.0);
    const ActorFrameStatistics b = hashed.processFrame(*wide->root, camera, 0.0);
    EXPECT_EQ(b.b + b.c1 + b.c2 + b.c3_1 + b.c3_2, a.b + a.c1 + a.c2 + a.c3_1 + a.c3_2 + 2) << "both far actors are seen";
    ASSERT_GT(a.occlusionCellsTested, 10u);
    EXPECT_EQ(b.occlusionCellsTested, a.occlusionCellsTested);
    EXPECT_EQ(b.occlusionCellsHidden, a.occlusionCellsHidden);
    EXPECT_GT(a.occlusionCellsHidden, 0u) << "the wall hides whole cells";
    for (ActorId id : near->ids) ASSERT_EQ(wide->crowd.actorClass(id), near->crowd.actorClass(id)) << "actor " << id;
}

// A narrow pillar hides a few actors of a wide crowd: with rest declared, the frame after the one
// that measured so little rests: no buffer, no test, every actor processed exactly as without
// occlusion (same classes, same draw list), whatever the threads; then it measures again.
TEST(Cascade, UnrewardingOcclusionRestsAndThenProcessesExactlyAsWithoutIt) {
    auto scene = makeRandomCrowd(12, 1500, 60.0);
    auto pillar = std::make_shared<Transform>();
    pillar->addChild(std::make_shared<Occluder>(std::vector<AxisBox>{AxisBox{glm::vec3(-6, -20, -1), glm::vec3(6, 20, 1)}},
                                                AxisBox{glm::vec3(-7, -21, -2), glm::vec3(7, 21, 2)}));
    scene->root->addChild(pillar);
    Camera camera;
    camera.setPerspective(1.0, 1.6, 0.1, 500.0);
    camera.setLookAt(Vec3(0, 5, 90), Vec3(0, 0, 0), Vec3(0, 1, 0));
    OcclusionSettings settings;
    settings.restFrames = 2;
    settings.restBelow = 0.2;

    std::vector<ActorClass> classesOff;
    std::vector<std::pair<ActorId, std::uint32_t>> drawnOff;
    {
        ActorProcessor plain(scene->crowd);
        plain.processFrame(*scene->root, camera, 0.1);
        for (ActorId id : scene->ids) classesOff.push_back(scene->crowd.actorClass(id));
        for (const DrawItem& item : plain.drawList().items()) drawnOff.emplace_back(item.actor, item.part);
    }
    for (unsigned threads : {1u, 2u}) {
        ActorProcessor resting(scene->crowd);
        resting.setThreads(threads);
        resting.setOcclusion(settings);
        const ActorFrameStatistics first = resting.processFrame(*scene->root, camera, 0.0);
        const std::uint64_t hidden = first.occludedWithGroup + first.occludedRefpoint + first.occludedSklsroot;
        EXPECT_FALSE(first.occlusionRested);
        ASSERT_GT(hidden, 0u) << "the pillar must hide someone";
        ASSERT_LT(double(hidden + first.nodesOccluded), 0.2 * double(first.occlusionObjectsTested)) << "and little";
        // Every actor tested after CULL 1 counts, alone or with its cell; so do the nodes and those after CULL 2.
        EXPECT_GE(first.occlusionObjectsTested, first.occlusionTests - first.occlusionCellsTested);

        const ActorFrameStatistics rest = resting.processFrame(*scene->root, camera, 0.1);
        EXPECT_TRUE(rest.occlusionRested);
        EXPECT_EQ(rest.occludersDrawn, 0u);
        EXPECT_EQ(rest.occlusionTests, 0u);
        EXPECT_EQ(rest.occlusionObjectsTested, 0u);
        EXPECT_EQ(rest.occlusionBufferMs, 0.0);
        EXPECT_EQ(rest.occludedWithGroup + rest.occludedRefpoint + rest.occludedSklsroot, 0u);
        std::vector<ActorClass> classes;
        for (ActorId id : scene->ids) classes.push_back(scene->crowd.actorClass(id));
        EXPECT_EQ(classes, classesOff) << threads << " threads";
        std::vector<std::pair<ActorId, std::uint32_t>> drawn;
        for (const DrawItem& item : resting.drawList().items()) drawn.emplace_back(item.actor, item.part);
        EXPECT_EQ(drawn, drawnOff) << threads << " threads";

        EXPECT_TRUE(resting.processFrame(*scene->root, camera, 0.2).occlusionRested);
        const ActorFrameStatistics again = resting.processFrame(*scene->root, camera, 0.3);
        EXPECT_FALSE(again.occlusionRested) << "the rest lasts restFrames frames";
        EXPECT_GT(again.occludedWithGroup + again.occludedRefpoint + again.occludedSklsroot, 0u);
    }
}

TEST(Cascade, AHeldObjectEnlargesBothSpheresAndIsDrawnWithTheActor) {
    Crowd crowd;
    const auto tmpl = makeSeedHumanoid();
    auto behaviour = std::make_shared<KeyframeBehaviour>();
    KeyframeBehaviour::Actor a;
    a.tmpl = tmpl;
    const ActorId id = crowd.add(tmpl, behaviour, behaviour->addActor(a));
    const double sklsBefore = crowd.skeletonRootRadius(id);
    const double refBefore = crowd.state().refSphereLocal[id].radius();
    // A 3 m pole in the right hand: the spheres must still hold it in every pose.
    auto pole = std::make_shared<MeshDrawable>(makeBox("pole", glm::vec3(0, -1.5f, 0), glm::vec3(0.02f, 1.5f, 0.02f)));
    const int hand = tmpl->findNode("rElbow");
    ASSERT_GE(hand, 0);
    crowd.hold(id, HeldObject{hand, pole});
    EXPECT_GT(crowd.skeletonRootRadius(id), sklsBefore + 1.0);
    EXPECT_NEAR(crowd.state().refSphereLocal[id].radius() - refBefore, crowd.skeletonRootRadius(id) - sklsBefore, 1e-9);
    EXPECT_THROW(crowd.hold(id, HeldObject{99, pole}), std::invalid_argument);
    EXPECT_THROW(crowd.hold(id, HeldObject{hand, nullptr}), std::invalid_argument);

    auto root = std::make_shared<Group>();
    root->addChild(crowd.makeActorNode(id));
    Camera camera;
    camera.setPerspective(1.0, 1.0, 0.1, 100.0);
    camera.setLookAt(Vec3(0, 1, 6), Vec3(0, 1, 0), Vec3(0, 1, 0));
    ActorProcessor processor(crowd);
    processor.processFrame(*root, camera, 0.3);
    bool poleDrawn = false;
    for (const DrawItem& item : processor.drawList().items()) poleDrawn = poleDrawn || item.drawable == pole.get();
    EXPECT_TRUE(poleDrawn);
    const auto actorPrimitives = primitives(processor.drawList());
    processor.setProcessing(Processing::Traditional);
    processor.processFrame(*root, camera, 0.3);
    EXPECT_TRUE(primitives(processor.drawList()) == actorPrimitives);
    // In every pose of the clip the pole stays inside the Sklsroot Bsphere.
    const auto& s = crowd.state();
    for (double t = 0; t < 2.0; t += 0.05) {
        processor.processFrame(*root, camera, t);
        for (const DrawItem& item : processor.drawList().items())
            if (item.drawable == pole.get()) {
                const BoundingSphere world = pole->localBound().transformed(item.world.toMat4());
                EXPECT_TRUE(BoundingSphere(Vec3(s.sklsWorld[id][3]), s.sklsRadius[id]).contains(world)) << t;
            }
    }
}

// Nodes destroyed in any order (a scene torn down or edited): the crowd forgets exactly those, their
// actors are held by no node and leave the frame, and the cascade still matches traditional
// processing on the nodes that remain.
TEST(Cascade, DestroyedNodesLeaveTheCrowdAndTheOthersStillDrawAsTraditionalProcessing) {
    auto scene = makeRandomCrowd(7, 600, 80.0);
    std::vector<std::shared_ptr<Node>> kept, removed;
    int i = 0;
    for (const auto& child : scene->root->children())
        if (child != scene->vehicle) (i++ % 3 == 1 ? removed : kept).push_back(child);
    ASSERT_GT(removed.size(), 20u);
    std::vector<ActorId> orphaned;
    for (const auto& node : removed) {
        for (ActorId id : scene->ids)
            if (scene->crowd.state().owner[id] == node.get()) orphaned.push_back(id);
        ASSERT_TRUE(scene->root->removeChild(node.get()));
    }
    // Destroy them middle first, then alternately from both ends.
    std::vector<std::shared_ptr<Node>> order;
    for (std::size_t lo = removed.size() / 2, hi = lo + 1; order.size() < removed.size();) {
        if (lo < removed.size()) order.push_back(removed[lo]);
        if (hi < removed.size()) order.push_back(removed[hi]);
        if (lo == 0) lo = removed.size(); else --lo;
        ++hi;
    }
    removed.clear();
    for (auto& node : order) node.reset();

    std::vector<const Node*> listed(scene->crowd.nodes().begin(), scene->crowd.nodes().end());
    std::vector<const Node*> expected;  // the actor and group nodes left under the root and on the vehicle
    for (const auto& node : kept) expected.push_back(node.get());
    for (const auto& child : scene->vehicle->children()) expected.push_back(child.get());
    std::sort(listed.begin(), listed.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(listed, expected) << "the crowd lists exactly the actor nodes left";
    for (ActorId id : orphaned) EXPECT_EQ(scene->crowd.state().owner[id], nullptr) << "actor " << id;

    Camera camera;
    camera.setPerspective(0.9, 1.6, 0.1, 500.0);
    camera.setLookAt(Vec3(0, 20, 120), Vec3(0, 0, 0));
    ActorProcessor cascade(scene->crowd);
    cascade.setBehaviouralLod(false);  // both methods then pose actors identically
    cascade.processFrame(*scene->root, camera, 1.0);
    for (const DrawItem& item : cascade.drawList().items())
        EXPECT_EQ(std::find(orphaned.begin(), orphaned.end(), item.actor), orphaned.end()) << "actor " << item.actor << " has no node";
    ActorProcessor traditional(scene->crowd);
    traditional.setProcessing(Processing::Traditional);
    traditional.processFrame(*scene->root, camera, 1.0);
    EXPECT_GT(cascade.drawList().items().size(), 0u);
    EXPECT_TRUE(primitives(cascade.drawList()) == primitives(traditional.drawList()));
}

namespace {

// Key-frame actors of which some are "simulated elsewhere": absent ones report a stale Reference
// Point (in front of the camera, where CULL 1 would keep them if it read it), and count how often
// it was asked for.
class PartlyPresent : public KeyframeBehaviour {
public:
    std::vector<std::uint8_t> absent;
    Vec3 stale{0.0};
    std::atomic<int> staleReads{0};
    Mat4 referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) override {
        if (slot < absent.size() && absent[slot]) {
            ++staleReads;
            Mat4 m(1.0);
            m[3] = Vec4(stale, 1.0);
            return m;
        }
        return KeyframeBehaviour::referencePoint(slot, context, ops);
    }
    void referencePoints(std::span<const std::uint32_t> slots, const FrameContext& context, OpTally* ops,
                         std::span<Mat4> out) override {
        for (std::size_t k = 0; k < slots.size(); ++k) out[k] = referencePoint(slots[k], context, ops);
    }
    bool presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const override {
        for (std::size_t k = 0; k < slots.size(); ++k) present[k] = slots[k] >= absent.size() || !absent[slots[k]];
        return false;
    }
};

struct LineOfActors {
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::shared_ptr<PartlyPresent> behaviour = std::make_shared<PartlyPresent>();
    std::shared_ptr<ActorGroup> group;
};

// `n` standing seed humanoids 2 m apart along x, centred on the origin, in one group node.
std::unique_ptr<LineOfActors> lineOfActors(int n) {
    auto s = std::make_unique<LineOfActors>();
    static const auto humanoid = makeSeedHumanoid();
    std::vector<ActorId> ids;
    for (int i = 0; i < n; ++i) {
        KeyframeBehaviour::Actor a;
        a.tmpl = humanoid;
        a.clip = humanoid->findClip("walk");
        a.position = Vec3(2.0 * (i - 0.5 * (n - 1)), 0.0, 0.0);
        ids.push_back(s->crowd.add(humanoid, s->behaviour, s->behaviour->addActor(a)));
    }
    s->group = s->crowd.makeGroupNode(ids);
    s->root->addChild(s->group);
    return s;
}

}  // namespace

// A declared roaming bound stands for a group's bound (members inside leave it as it is, one
// outside widens it), and it changes nothing the cascade decides; actors another process holds and
// did not send (not present) are rejected by CULL 1 without reading their stale state or testing
// it, and everything else is processed as if they were there.
TEST(Cascade, ARoamingBoundStandsForTheGroupAndAbsentActorsAreRejectedUnread) {
    Camera camera;
    camera.setPerspective(0.8, 1.5, 0.1, 200.0);
    camera.setLookAt(Vec3(-20.0, 2.0, 25.0), Vec3(-20.0, 1.0, 0.0), Vec3(0, 1, 0));  // sees the left end of the line
    auto grown = lineOfActors(60), roaming = lineOfActors(60);
    roaming->group->setRoamingBound(BoundingSphere(Vec3(0.0), 200.0));
    ActorProcessor pg(grown->crowd), pr(roaming->crowd);
    const ActorFrameStatistics a = pg.processFrame(*grown->root, camera, 0.5);
    const std::size_t grownItems = pg.drawList().size();
    ASSERT_GT(a.a, 10u) << "the right end lies outside the view";
    ASSERT_GT(grownItems, 0u);
    const ActorFrameStatistics b = pr.processFrame(*roaming->root, camera, 0.5);
    EXPECT_EQ(roaming->group->worldBound(), BoundingSphere(Vec3(0.0), 200.0)) << "the declared bound stands";
    EXPECT_EQ(b.a, a.a);
    EXPECT_EQ(b.spheresTested, a.spheresTested);
    EXPECT_EQ(pr.drawList().size(), grownItems);

    // Those outside the view are absent, their stale Reference Points right in front of the camera.
    roaming->behaviour->absent.assign(60, 0);
    std::size_t absent = 0;
    for (std::uint32_t i = 0; i < 60; ++i)
        if (grown->crowd.actorClass(ActorId(i)) == ActorClass::A) roaming->behaviour->absent[i] = 1, ++absent;
    roaming->behaviour->stale = Vec3(-20.0, 0.0, 10.0);
    const ActorFrameStatistics c = pr.processFrame(*roaming->root, camera, 0.5);
    EXPECT_EQ(absent, a.a);
    EXPECT_EQ(c.a, a.a) << "absent actors are rejected at CULL 1";
    EXPECT_EQ(c.spheresTested, a.spheresTested - absent) << "without a test";
    EXPECT_EQ(roaming->behaviour->staleReads.load(), 0) << "their stale Reference Points are not read";
    EXPECT_EQ(c.primitives, a.primitives);
    EXPECT_EQ(pr.drawList().size(), grownItems) << "nothing stale is drawn";
    for (std::uint32_t i = 0; i < 60; ++i) EXPECT_EQ(roaming->crowd.actorClass(ActorId(i)), grown->crowd.actorClass(ActorId(i))) << i;

    // A member outside the declared bound widens it.
    auto one = lineOfActors(1);
    one->group->setRoamingBound(BoundingSphere(Vec3(0.0, 0.0, 500.0), 5.0));
    ActorProcessor po(one->crowd);
    po.processFrame(*one->root, camera, 0.0);
    EXPECT_TRUE(one->group->worldBound().contains(one->crowd.state().refSphereWorld[0])) << "widened to hold its member";
    // A lone member's own sphere is still tested at CULL 1 (the node's bound is not its sphere).
    one->group->setRoamingBound(BoundingSphere(Vec3(0.0), 300.0));
    Camera away;
    away.setPerspective(0.8, 1.5, 0.1, 2000.0);
    away.setLookAt(Vec3(0.0, 2.0, 100.0), Vec3(0.0, 1.0, 200.0), Vec3(0, 1, 0));  // sees the bound, not the actor
    const ActorFrameStatistics d = po.processFrame(*one->root, away, 0.0);
    EXPECT_EQ(d.a, 1u) << "the lone member is rejected at CULL 1";
    EXPECT_EQ(d.c1, 0u);
    EXPECT_EQ(po.drawList().size(), 0u);
}

namespace {

// Walkers of which those in `here` are present, listing their present slots (Behaviour::
// presentSlots) when `lists`: a crowd then visits only those; otherwise every actor is asked.
class ListedWalkers : public KeyframeShare {
public:
    bool lists = true;
    std::vector<std::uint32_t> slots;  // the present ones, increasing
    std::optional<std::span<const std::uint32_t>> presentSlots() const override {
        if (!lists) return std::nullopt;
        return std::span<const std::uint32_t>(slots);
    }
    void choose(std::mt19937& rng, double share) {
        std::bernoulli_distribution in(share);
        slots.clear();
        for (std::size_t k = 0; k < here.size(); ++k)
            if ((here[k] = in(rng))) slots.push_back(std::uint32_t(k));
    }
};

// 300 listed walkers in two groups (the first numbered against its members' order), and 40 actors
// of another behaviour, always present, in a third.
struct ListedScene {
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::shared_ptr<ListedWalkers> walkers = std::make_shared<ListedWalkers>();
    std::shared_ptr<KeyframeBehaviour> others = std::make_shared<KeyframeBehaviour>();
};

std::unique_ptr<ListedScene> listedScene() {
    static const auto humanoid = makeSeedHumanoid();
    auto s = std::make_unique<ListedScene>();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-40.0, 40.0);
    std::vector<ActorId> groups[3];
    for (int i = 0; i < 340; ++i) {
        KeyframeBehaviour::Actor a;
        a.tmpl = humanoid;
        a.clip = humanoid->findClip("walk");
        a.position = Vec3(u(rng), 0.0, u(rng));
        a.pathRadius = 3.0, a.pathSpeed = 1.2;
        const bool walker = i < 300;
        auto& behaviour = walker ? static_cast<KeyframeBehaviour&>(*s->walkers) : *s->others;
        const ActorId id = s->crowd.add(humanoid, walker ? std::shared_ptr<Behaviour>(s->walkers) : s->others, behaviour.addActor(a));
        groups[walker ? i % 2 : 2].push_back(id);
    }
    std::reverse(groups[0].begin(), groups[0].end());
    for (auto& ids : groups) {
        auto group = s->crowd.makeGroupNode(ids);
        group->setRoamingBound(BoundingSphere(Vec3(0.0), 60.0));
        s->root->addChild(group);
    }
    s->walkers->here.assign(300, 1);
    return s;
}

}  // namespace

// A behaviour listing its present slots: the crowd visits only those (and the actors of behaviours
// listing none), and the frame is the one a visit of every actor makes, frame after frame, as
// actors come and go.
TEST(Cascade, VisitingOnlyTheListedActorsMakesTheFrameEveryActorsVisitMakes) {
    auto listed = listedScene(), asked = listedScene();
    asked->walkers->lists = false;
    ActorProcessor pl(listed->crowd), pa(asked->crowd);
    Camera camera;
    camera.setPerspective(1.0, 1.5, 0.1, 300.0);
    std::mt19937 rng(9);
    for (int f = 0; f < 12; ++f) {
        SCOPED_TRACE("frame " + std::to_string(f));
        std::mt19937 same(rng());
        listed->walkers->choose(same, f == 5 ? 1.0 : 0.3);  // frame 5: everyone present
        same.seed(rng());
        asked->walkers->here = listed->walkers->here, asked->walkers->slots = listed->walkers->slots;
        camera.setLookAt(Vec3(-50.0 + 5.0 * f, 2.0, 60.0), Vec3(0.0, 0.0, 0.0), Vec3(0, 1, 0));
        const ActorFrameStatistics a = pa.processFrame(*asked->root, camera, 0.1 * f);
        const ActorFrameStatistics l = pl.processFrame(*listed->root, camera, 0.1 * f);
        EXPECT_EQ(l.actorsInScene, a.actorsInScene);
        EXPECT_EQ(l.actorsAbsent, a.actorsAbsent);
        EXPECT_EQ(l.culledWithGroup, a.culledWithGroup);
        EXPECT_EQ(l.a, a.a);
        EXPECT_EQ(l.b, a.b);
        EXPECT_EQ(l.c1, a.c1);
        EXPECT_EQ(l.c2, a.c2);
        EXPECT_EQ(l.spheresTested, a.spheresTested);
        ASSERT_EQ(pl.drawList().size(), pa.drawList().size());
        EXPECT_GT(pa.drawList().size(), 50u);
        auto item = pa.drawList().items().begin();
        for (const DrawItem& i : pl.drawList().items()) {
            const DrawItem& e = *item++;
            ASSERT_EQ(i.actor, e.actor);
            ASSERT_EQ(i.part, e.part);
            ASSERT_TRUE(i.world == e.world);
        }
        for (ActorId id = 0; id < 340; ++id) {
            ASSERT_EQ(listed->crowd.actorClass(id), asked->crowd.actorClass(id)) << "actor " << id;
            ASSERT_EQ(listed->crowd.state().present[id], asked->crowd.state().present[id]) << "actor " << id;
        }
        if (f == 5) EXPECT_EQ(l.actorsAbsent, 0u);
        else EXPECT_GT(l.actorsAbsent, 150u);
    }
}
