// Templates: the seed's humanoid and the Table 3 actor have the structure the papers give; building
// validates skeletal LOD against vaLod (errors name the node); the Sklsroot radius bounds every
// sampled pose; clones share their template and report what one more costs.

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <random>
#include <set>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/testkit/Errors.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/Table3Template.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"

using namespace throng;

namespace {

std::shared_ptr<const Drawable> piece(const char* name) {
    return std::make_shared<MeshDrawable>(makeBox(name, glm::vec3(0), glm::vec3(0.1f)));
}

SkeletonNode joint(const char* name, int parent, double deactivation = std::numeric_limits<double>::infinity()) {
    SkeletonNode n;
    n.name = name;
    n.parent = parent;
    n.restTranslation = glm::vec3(0, 0.3f, 0);
    n.dofs = {Dof::rotation(glm::vec3(1, 0, 0), -1.0f, 1.0f)};
    n.deactivationDistance = deactivation;
    return n;
}

template <class F>
std::string errorOf(F&& f) { return testkit::errorOf<std::invalid_argument>(std::forward<F>(f)); }

}  // namespace

TEST(Templates, SeedHumanoidHas13ArticulationPoints19DofsAnd5GeometricLods) {
    const auto h = makeSeedHumanoid();
    EXPECT_EQ(h->nodeCount(), 13u);
    EXPECT_EQ(h->dofCount(), 19u);
    // Five geometric levels: the distinct level ends of every vaLod that draws something.
    std::set<double> ends;
    for (const SkeletonNode& n : h->nodes())
        for (const VaLodLevel& l : n.geometry.levels())
            if (l.drawable) ends.insert(l.maxDistance);
    for (const VaLodLevel& l : h->rootGeometry().levels())
        if (l.drawable) ends.insert(l.maxDistance);
    EXPECT_EQ(ends.size(), 5u);
    // Skeletal levels shrink with distance, down to none (the seed's "LOD formed by none").
    std::vector<std::uint8_t> active(h->nodeCount());
    EXPECT_EQ(computeActiveNodes(*h, 5.0 * 5.0, active), 13u);
    EXPECT_EQ(computeActiveNodes(*h, 20.0 * 20.0, active), 12u);   // eyes off
    EXPECT_EQ(computeActiveNodes(*h, 50.0 * 50.0, active), 10u);   // head and neck off
    EXPECT_EQ(computeActiveNodes(*h, 100.0 * 100.0, active), 6u);  // elbows and knees off
    EXPECT_EQ(computeActiveNodes(*h, 300.0 * 300.0, active), 0u);
    EXPECT_GE(h->findClip("walk"), 0);
    EXPECT_GE(h->findClip("pirouette"), 0);
}

TEST(Templates, Table3ActorHas40Nodes80SpheresAnd41LodNodes) {
    const auto t = makeTable3Template();
    EXPECT_EQ(t->nodeCount(), 40u);
    EXPECT_EQ(t->dofCount(), 80u) << "2 DOFs per Skeleton node on average";
    EXPECT_EQ(t->internalSphereCount(), 80u);
    std::size_t lodNodes = t->rootGeometry().empty() ? 0 : 1;
    for (const SkeletonNode& n : t->nodes()) lodNodes += !n.geometry.empty();
    EXPECT_EQ(lodNodes, 41u);
    std::vector<std::uint8_t> active(t->nodeCount());
    EXPECT_EQ(computeActiveNodes(*t, 10.0 * 10.0, active), 40u);
    EXPECT_EQ(computeActiveNodes(*t, 100.0 * 100.0, active), 20u) << "skeletal LOD halves the nodes (fLODtopo)";
}

TEST(Templates, GeometryShownBeyondTheDeactivationDistanceIsRejectedNamingTheNode) {
    ActorTemplateBuilder b("bad");
    SkeletonNode hip = joint("hip", -1, 100.0);
    hip.geometry.addLevel(100.0, piece("thigh"));
    b.addNode(hip);
    SkeletonNode knee = joint("knee", 0, 50.0);
    knee.geometry.addLevel(80.0, piece("shin"));  // still drawn at 80 m, but off at 50 m
    b.addNode(knee);
    const std::string msg = errorOf([&] { b.build(); });
    EXPECT_NE(msg.find("'knee'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("80"), std::string::npos) << msg;
    EXPECT_NE(msg.find("50"), std::string::npos) << msg;
}

TEST(Templates, AChildActiveBeyondItsParentIsRejectedNamingIt) {
    ActorTemplateBuilder b("bad");
    b.addNode(joint("shoulder", -1, 60.0));
    b.addNode(joint("finger", 0, 90.0));
    const std::string msg = errorOf([&] { b.build(); });
    EXPECT_NE(msg.find("'finger'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'shoulder'"), std::string::npos) << msg;
}

TEST(Templates, BadNodesAndClipsAreRejectedWithClearErrors) {
    ActorTemplateBuilder b("bad");
    b.addNode(joint("a", -1));
    b.addNode(joint("b", 0));
    b.addNode(joint("c", -1));
    EXPECT_NE(errorOf([&] { b.addNode(joint("d", 1)); }).find("depth-first"), std::string::npos);
    EXPECT_NE(errorOf([&] { b.addNode(joint("a", -1)); }).find("already used"), std::string::npos);
    SkeletonNode zeroAxis = joint("z", -1);
    zeroAxis.dofs[0].axis = glm::vec3(0);
    EXPECT_NE(errorOf([&] { b.addNode(zeroAxis); }).find("axis"), std::string::npos);
    SkeletonNode badLimits = joint("l", -1);
    badLimits.dofs[0].min = 1.0f;
    badLimits.dofs[0].max = -1.0f;
    EXPECT_NE(errorOf([&] { b.addNode(badLimits); }).find("limits"), std::string::npos);
    SkeletonNode nan = joint("n", -1);
    nan.restTranslation.x = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(errorOf([&] { b.addNode(nan); }).find("non-finite"), std::string::npos);

    ClipChannel c;
    c.node = 1;
    c.dof = 3;
    c.times = {0.0f, 1.0f};
    c.values = {0.0f, 1.0f};
    b.addClip(std::make_shared<AnimationClip>("wave", std::vector<ClipChannel>{c}));
    const std::string msg = errorOf([&] { b.build(); });
    EXPECT_NE(msg.find("clip 'wave', channel 0"), std::string::npos) << msg;
    EXPECT_NE(msg.find("DOF 3"), std::string::npos) << msg;

    ClipChannel unordered = c;
    unordered.dof = 0;
    unordered.times = {1.0f, 0.5f};
    EXPECT_NE(errorOf([&] { AnimationClip("bad", {unordered}); }).find("not strictly increasing"), std::string::npos);
}

namespace {
// Farthest any part gets from the Skeleton Root: culling needs every part inside the Sklsroot
// Bsphere (the merged sphere of all parts may reach farther than any part does).
double farthestPart(const ActorTemplate& t, std::span<const BoundingSphere> geometry) {
    double far = 0.0;
    const BoundingSphere root = t.rootGeometry().bound();
    if (root.valid()) far = glm::length(root.center()) + root.radius();
    for (const BoundingSphere& g : geometry)
        if (g.valid()) far = std::max(far, glm::length(g.center()) + g.radius());
    return far;
}
}  // namespace

TEST(Templates, SklsrootRadiusHoldsEveryPoseOfEveryClipAndReachHoldsAnyPose) {
    for (const auto& t : {makeSeedHumanoid(), makeTable3Template()}) {
        EXPECT_LE(t->skeletonRootRadius(), t->reachRadius() + 1e-12) << t->name();
        std::vector<Affine> model(t->nodeCount());
        std::vector<BoundingSphere> g(t->nodeCount()), sub(t->nodeCount());
        for (const auto& clip : t->clips())
            for (double time = 0; time <= clip->duration(); time += 0.013) {
                std::vector<float> dofs(t->restDofs().begin(), t->restDofs().end());
                clip->sample(*t, time, false, {}, dofs);
                computeModelTransforms(*t, dofs, {}, model);
                computeInternalSpheres(*t, model, {}, g, sub);
                EXPECT_LE(farthestPart(*t, g), t->skeletonRootRadius()) << t->name() << " clip " << clip->name() << " t " << time;
            }
        // Any pose within the limits stays within the reach radius.
        std::mt19937_64 rng(3);
        for (int k = 0; k < 200; ++k) {
            std::vector<float> dofs(t->restDofs().begin(), t->restDofs().end());
            for (std::size_t i = 0; i < t->nodeCount(); ++i)
                for (std::size_t d = 0; d < t->nodes()[i].dofs.size(); ++d) {
                    const Dof& dof = t->nodes()[i].dofs[d];
                    if (dof.kind == DofKind::RotateAxis)
                        dofs[t->dofValueOffset(i, d)] = std::uniform_real_distribution<float>(dof.min, dof.max)(rng);
                }
            computeModelTransforms(*t, dofs, {}, model);
            computeInternalSpheres(*t, model, {}, g, sub);
            EXPECT_LE(farthestPart(*t, g), t->reachRadius() * (1 + 1e-6)) << t->name();
        }
    }
}

TEST(Templates, ClonesShareTheTemplateAndOneMoreCloneIsSmall) {
    const auto h = makeSeedHumanoid();
    Crowd crowd;
    auto behaviour = std::make_shared<KeyframeBehaviour>();
    for (int i = 0; i < 100; ++i) testkit::addKeyframed(crowd, h, behaviour);
    for (ActorId id = 0; id < crowd.size(); ++id) EXPECT_EQ(crowd.state().tmpl[id], h.get()) << "clones share the template";
    const std::size_t perClone = crowd.bytesPerActor(*h);
    const std::size_t shared = h->sharedBytes();
    EXPECT_GT(perClone, 0u);
    EXPECT_LT(perClone, 1024u) << "a clone's own state";
    EXPECT_GT(shared, 50u * perClone) << "geometry and clips are shared";
    RecordProperty("bytesPerClone", std::to_string(perClone));
    RecordProperty("sharedBytes", std::to_string(shared));
    std::printf("humanoid: %zu bytes shared by every clone, %zu bytes per clone\n", shared, perClone);
    EXPECT_EQ(crowd.dofs(7).size(), h->dofValueCount());
}

// The pose jobs validate the spans their callers own, and name the argument that is too short.
TEST(PoseJobs, ShortSpansAreRejectedNamingTheArgument) {
    const auto t = makeSeedHumanoid();
    const std::size_t n = t->nodeCount();
    std::vector<float> dofs(t->restDofs().begin(), t->restDofs().end());
    std::vector<std::uint8_t> active(n, 1);
    std::vector<Affine> model(n);
    std::vector<BoundingSphere> geometry(n), subtree(n);
    auto expectNamed = [](const std::function<void()>& call, const std::string& argument) {
        try {
            call();
            ADD_FAILURE() << "a short '" << argument << "' was accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("'" + argument + "'"), std::string::npos) << e.what();
        }
    };
    const std::span<float> shortDofs(dofs.data(), dofs.size() - 1);
    const std::span<std::uint8_t> shortActive(active.data(), n - 1);
    const std::span<Affine> shortModel(model.data(), n - 1);
    expectNamed([&] { computeActiveNodes(*t, 1.0, shortActive); }, "active");
    expectNamed([&] { computeModelTransforms(*t, shortDofs, {}, model); }, "dofs");
    expectNamed([&] { computeModelTransforms(*t, dofs, shortActive, model); }, "active");
    expectNamed([&] { computeModelTransforms(*t, dofs, {}, shortModel); }, "model");
    expectNamed([&] { computeInternalSpheres(*t, shortModel, {}, geometry, subtree); }, "model");
    expectNamed([&] { computeInternalSpheres(*t, model, {}, std::span(geometry.data(), n - 1), subtree); }, "geometry");
    expectNamed([&] { computeInternalSpheres(*t, model, {}, geometry, std::span(subtree.data(), n - 1)); }, "subtree");
    expectNamed([&] { writeRestPose(*t, {}, shortDofs); }, "dofs");
    expectNamed([&] { t->clips()[0]->sample(*t, 0.5, true, {}, shortDofs); }, "dofs");
    expectNamed([&] { t->clips()[0]->sample(*t, 0.5, true, shortActive, dofs); }, "active");
    // Full-size spans (and empty active flags, meaning every node) are accepted.
    EXPECT_EQ(computeModelTransforms(*t, dofs, {}, model), n);
    EXPECT_EQ(computeActiveNodes(*t, 1.0, active), n);
}
