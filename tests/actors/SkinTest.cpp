// Skinned templates: joint palettes (bind pose gives identity; a deactivated joint follows its
// nearest active ancestor), skinned pieces drawn with their palette by both methods and culled by
// their joints' spheres in the current pose.

#include <gtest/gtest.h>

#include <numbers>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/testkit/Cameras.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"

using namespace throng;
using namespace throng::testkit;

TEST(Skin, PaletteIsIdentityInTheBindPoseAndMovesVerticesWithTheirJoint) {
    const auto t = skinnedBar();
    std::vector<Affine> model(2);
    std::vector<glm::mat4> palette(2);
    std::vector<float> dofs(t->restDofs().begin(), t->restDofs().end());
    computeModelTransforms(*t, dofs, {}, model);
    computeSkinPalette(*t, t->skins()[0], model, {}, palette);
    for (const glm::mat4& m : palette)
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], c == r ? 1.0f : 0.0f, 1e-6);
    dofs[0] = std::numbers::pi_v<float> / 2.0f;  // the arm turns 90 degrees about Z
    computeModelTransforms(*t, dofs, {}, model);
    computeSkinPalette(*t, t->skins()[0], model, {}, palette);
    const glm::vec4 tip = palette[1] * glm::vec4(0, 2, 0, 1);
    EXPECT_NEAR(tip.x, -1.0f, 1e-6);
    EXPECT_NEAR(tip.y, 1.0f, 1e-6);
    // Deactivated, the arm follows its active ancestor as it was bound.
    const std::vector<std::uint8_t> baseOnly = {1, 0};
    computeSkinPalette(*t, t->skins()[0], model, baseOnly, palette);
    const glm::vec4 still = palette[1] * glm::vec4(0, 2, 0, 1);
    EXPECT_NEAR(still.x, 0.0f, 1e-6);
    EXPECT_NEAR(still.y, 2.0f, 1e-6);
}

TEST(Skin, BothMethodsDrawTheSkinnedMeshWithItsPaletteAndCullItByItsJoints) {
    const auto t = skinnedBar();
    Crowd crowd;
    auto root = std::make_shared<Group>();
    root->addChild(crowd.makeActorNode(testkit::addKeyframed(crowd, t, std::make_shared<KeyframeBehaviour>())));
    const Camera camera = testkit::lookingAt(Vec3(0, 1, 5), Vec3(0, 1, 0), {1.0, 1.0, 0.1, 100.0});
    ActorProcessor p(crowd);
    for (Processing m : {Processing::Actor, Processing::Traditional}) {
        p.setProcessing(m);
        p.processFrame(*root, camera, 1.0);  // fully bent
        ASSERT_EQ(p.drawList().size(), 1u);
        const DrawItem& item = p.drawList().items()[0];
        ASSERT_EQ(item.skinPaletteSize, 2u);
        const glm::vec4 tip = item.skinPalette[1] * glm::vec4(0, 2, 0, 1);
        EXPECT_NEAR(tip.x, -1.0f, 1e-5);
    }
    // Looking where only the bent arm is: the bind-pose box is out of view, but the arm is not,
    // so the mesh is drawn (it is culled by its joints' spheres in the current pose).
    Camera side;
    side.setPerspective(0.3, 1.0, 0.1, 100.0);
    side.setLookAt(Vec3(-1.0, 1.0, 5.0), Vec3(-1.0, 1.0, 0.0), Vec3(0, 1, 0));
    for (Processing m : {Processing::Actor, Processing::Traditional}) {
        p.setProcessing(m);
        p.processFrame(*root, side, 1.0);
        EXPECT_EQ(p.drawList().size(), 1u) << (m == Processing::Actor ? "actor" : "traditional");
    }
}

TEST(Skin, BadSkinsAreRejected) {
    ActorTemplateBuilder b("bad");
    SkeletonNode n;
    n.name = "only";
    b.addNode(n);
    b.addSkin(Skin{"s", {0, 3}});
    EXPECT_THROW(b.build(), std::invalid_argument);
    ActorTemplateBuilder c("bad2");
    c.addNode(n);
    const int skin = c.addSkin(Skin{"s", {0}});
    auto mesh = makeBox("m", glm::vec3(0), glm::vec3(1));
    for (std::size_t i = 0; i < mesh->positions.size(); ++i) {
        mesh->joints0.push_back(glm::u16vec4(2, 0, 0, 0));
        mesh->weights0.push_back(glm::vec4(1, 0, 0, 0));
    }
    c.rootGeometry().addLevel(10.0, std::make_shared<MeshDrawable>(mesh), skin);
    try {
        c.build();
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("refers to joint 2"), std::string::npos) << e.what();
    }
}
