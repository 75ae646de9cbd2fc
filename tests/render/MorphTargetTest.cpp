// Morph targets in the renderer (glTF "targets", faces): offsets added with per-item weights before
// skinning, on the GPU (offsets in a buffer texture, only the non-zero weights read per instance)
// and on the CPU path, which is the reference the GPU is held to.
//
//   * applyMorphTargets and skinMesh on a hand-made mesh: targets go before the skin (a vertex
//     offset along x by a joint turned 90 degrees ends up offset along y), weights clamped, every
//     bad input named.
//   * A skinned tube with a "bulge" target, bent: the GPU frame agrees with the CPU path's, and
//     both with a reference drawn from vertices morphed then skinned on the CPU; a reference that
//     adds the offsets after skinning is far off (so the test fails if the shader did so).
//   * RobotExpressive's face (Angry / Surprised / Sad on its three rigid head meshes), driven
//     through the actor pipeline (a clip's morph-weight channels -> the actor's DOFs -> draw items):
//     neutral, Angry 1.0, and Surprised 0.5 + Sad 0.5, each a golden image
//     (golden/robot_face_*.png), GPU and CPU within kMorphAgreement of each other, the three
//     expressions apart from each other, and the offsets added in the world frame instead far off.

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <map>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "RenderTestSupport.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/render/CpuSkinning.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/OsMesaContext.h"
#include "throng/render/ProceduralMeshes.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/testkit/CharacterStage.h"
#include "throng/testkit/Characters.h"

namespace throng {
namespace {

constexpr int kSize = testkit::kCharacterFrameSize;

// GPU and CPU morphing compute the same sums in the same order (targets ascending, zero weights
// skipped); like CPU and GPU skinning (CharacterRenderTest) they may differ by float rounding only:
// at most 0.3 % of the pixels more than 8/255 apart and a PSNR of at least 40 dB.
const test::GoldenTolerance kMorphAgreement{8, 0.003, 40.0};

TEST(MorphTargets, CpuReferenceAddsWeightedOffsetsBeforeSkinning) {
    MeshData m;
    m.name = "triangle";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    m.indices = {0, 1, 2};
    m.joints0.assign(3, glm::u16vec4(0));
    m.weights0.assign(3, glm::vec4(1, 0, 0, 0));
    m.morphTargets.push_back({"along x", std::vector<glm::vec3>(3, glm::vec3(1, 0, 0)), {}, 0.0f});
    m.morphTargets.push_back({"vertex 0 up", {{0, 0, 1}, {0, 0, 0}, {0, 0, 0}}, {{1, 0, 0}, {0, 0, 0}, {0, 0, 0}}, 0.0f});
    ASSERT_NO_THROW(m.validate());
    const std::vector<float> weights{0.5f, 3.0f};  // the second is clamped to 1
    std::vector<glm::vec3> p(3), n(3);
    applyMorphTargets(m, weights, p, n);
    EXPECT_EQ(p[0], glm::vec3(0.5f, 0, 1));
    EXPECT_EQ(p[1], glm::vec3(1.5f, 0, 0));
    EXPECT_EQ(n[0], glm::vec3(1, 0, 1));  // unnormalised: skinning normalises
    // A joint turned 90 degrees about z, scaled 2, moved up 1: the offset along x becomes one along y.
    const glm::mat4 joint = glm::scale(glm::rotate(glm::translate(glm::mat4(1), glm::vec3(0, 1, 0)), float(std::numbers::pi / 2),
                                                   glm::vec3(0, 0, 1)),
                                       glm::vec3(2.0f));
    const std::vector<glm::mat4> palette{joint};
    std::vector<glm::vec3> skinned(3), skinnedNormals(3);
    skinMesh(m, palette, skinned, skinnedNormals, p, n);
    for (int v = 0; v < 3; ++v) {
        const glm::vec3 before = glm::vec3(joint * glm::vec4(p[v], 1.0f));
        EXPECT_NEAR(glm::distance(skinned[v], before), 0.0f, 1e-5f) << "vertex " << v;
        const glm::vec3 after = glm::vec3(joint * glm::vec4(m.positions[v], 1.0f)) + (p[v] - m.positions[v]);
        EXPECT_GT(glm::distance(skinned[v], after), 0.9f) << "vertex " << v << ": offsets added after skinning";
    }
    EXPECT_NEAR(skinned[1].y, 1.0f + 2.0f * 1.5f, 1e-5f);
    // In place, as the renderer's CPU path does it.
    std::vector<glm::vec3> inPlace = p, inPlaceNormals = n;
    skinMesh(m, palette, inPlace, inPlaceNormals, inPlace, inPlaceNormals);
    EXPECT_EQ(inPlace, skinned);
    // Zero weights: the mesh as it is.
    applyMorphTargets(m, std::vector<float>{0.0f, 0.0f}, p, n);
    EXPECT_EQ(p, m.positions);
    // Bad input, named.
    EXPECT_THROW(applyMorphTargets(m, std::vector<float>{1.0f}, p, n), std::invalid_argument);
    EXPECT_THROW(applyMorphTargets(m, std::vector<float>{NAN, 0.0f}, p, n), std::invalid_argument);
    std::vector<glm::vec3> two(2);
    EXPECT_THROW(applyMorphTargets(m, weights, two, n), std::invalid_argument);
    EXPECT_THROW(skinMesh(m, palette, skinned, skinnedNormals, two, {}), std::invalid_argument);
}

TEST(MorphTargets, MeshValidationNamesTheBadTarget) {
    MeshData m;
    m.name = "quad";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2};
    const auto fails = [&](MorphTarget t, const std::string& expected) {
        MeshData bad = m;
        bad.morphTargets = {MorphTarget{"first", std::vector<glm::vec3>(3), {}, 0.0f}, std::move(t)};
        try {
            bad.validate();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what()).find(expected) != std::string::npos ? std::string() : std::string(e.what());
        }
        return std::string("(valid)");
    };
    EXPECT_EQ(fails({"", std::vector<glm::vec3>(3), {}, 0.0f}, "morph target 1 has no name"), "");
    EXPECT_EQ(fails({"first", std::vector<glm::vec3>(3), {}, 0.0f}, "has the name of morph target 0"), "");
    EXPECT_EQ(fails({"short", std::vector<glm::vec3>(2), {}, 0.0f}, "has 2 position offsets for 3 vertices"), "");
    EXPECT_EQ(fails({"nan", {{0, 0, 0}, {0, NAN, 0}, {0, 0, 0}}, {}, 0.0f}, "the offset of vertex 1 is not finite"), "");
    EXPECT_EQ(fails({"normals", std::vector<glm::vec3>(3), std::vector<glm::vec3>(3), 0.0f}, "normal offsets for 0 normals"), "");
    EXPECT_EQ(fails({"weight", std::vector<glm::vec3>(3), {}, INFINITY}, "non-finite default weight"), "");
}

class MorphRenderTest : public ::testing::Test {
protected:
    std::shared_ptr<OsMesaContext> context = std::make_shared<OsMesaContext>(kSize, kSize);
};

// A frame of `list` seen by `camera`.
Image renderList(GlRenderer& renderer, const Camera& camera, const DrawList& list) {
    renderer.beginFrame(camera);
    renderer.draw(list);
    Image image = renderer.readFrame();
    renderer.endFrame();
    return image;
}

TEST_F(MorphRenderTest, SkinnedTubeMorphsOnTheGpuAsOnTheCpuBeforeSkinning) {
    SkinnedTubeOptions o;
    o.joints = 4;
    o.bands = 2;
    auto tube = makeSkinnedTube(o);
    // "bulge": the upper half pushed out radially by 60 % and its normals tipped up.
    MorphTarget bulge{"bulge", {}, {}, 0.0f};
    for (const glm::vec3& p : tube->positions) bulge.positions.push_back(p.y > 1.0f ? glm::vec3(0.6f * p.x, 0, 0.6f * p.z) : glm::vec3(0));
    for (const glm::vec3& p : tube->positions) bulge.normals.push_back(p.y > 1.0f ? glm::vec3(0, 0.5f, 0) : glm::vec3(0));
    tube->morphTargets.push_back(bulge);
    tube->morphTargets.push_back(MorphTarget{"unused", std::vector<glm::vec3>(tube->vertexCount(), glm::vec3(1, 0, 0)), {}, 0.0f});
    std::vector<glm::mat4> palette;
    bendTubePalette(o, 0.5f, palette);
    const std::vector<float> weights{1.0f, 0.0f};
    const auto drawable = test::drawable(tube);
    DrawItem item;
    item.drawable = drawable.get();
    item.world = ItemTransform(Mat4(1.0));
    item.skinPalette = palette.data();
    item.skinPaletteSize = static_cast<std::uint32_t>(palette.size());
    item.morphWeights = weights.data();
    DrawList list;
    list.add(item, drawable->primitiveCount());
    const Camera camera = test::makeCamera(Vec3(0.0, 1.2, 5.0), Vec3(0.0, 1.0, 0.0));
    GlRenderer renderer(context);
    const Image gpu = renderList(renderer, camera, list);
    EXPECT_EQ(renderer.statistics().morphInstances, 1u);
    EXPECT_EQ(renderer.statistics().morphTargetsRead, 1u) << "the zero weight is not read";
    EXPECT_EQ(renderer.statistics().gpuSkinnedVertices, tube->vertexCount());
    RendererOptions cpuOptions = renderer.options();
    cpuOptions.forceCpuSkinning = true;
    renderer.setOptions(cpuOptions);
    const Image cpu = renderList(renderer, camera, list);
    EXPECT_EQ(renderer.statistics().cpuSkinnedVertices, tube->vertexCount());
    EXPECT_EQ(test::disagreement(gpu, cpu, kMorphAgreement), "");
    renderer.setOptions(RendererOptions{});
    // References drawn rigid from vertices computed here: morphed then skinned, and skinned then
    // offset.
    const auto rigidOf = [&](const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals) {
        auto mesh = std::make_shared<MeshData>(*tube);
        mesh->positions = positions;
        mesh->normals = normals;
        mesh->joints0.clear(), mesh->weights0.clear(), mesh->morphTargets.clear();
        return test::drawable(mesh);
    };
    const std::size_t n = tube->vertexCount();
    std::vector<glm::vec3> mp(n), mn(n), sp(n), sn(n);
    applyMorphTargets(*tube, weights, mp, mn);
    skinMesh(*tube, palette, sp, sn, mp, mn);
    const auto before = rigidOf(sp, sn);
    skinMesh(*tube, palette, sp, sn);
    for (std::size_t v = 0; v < n; ++v) sp[v] += mp[v] - tube->positions[v];
    const auto after = rigidOf(sp, sn);
    for (const auto& [reference, agrees] : {std::pair{before, true}, std::pair{after, false}}) {
        DrawItem r;
        r.drawable = reference.get();
        r.world = ItemTransform(Mat4(1.0));
        DrawList rl;
        rl.add(r, reference->primitiveCount());
        const Image image = renderList(renderer, camera, rl);
        if (agrees) EXPECT_EQ(test::disagreement(gpu, image, kMorphAgreement), "") << "the GPU does not morph before skinning";
        else EXPECT_NE(test::disagreement(gpu, image, kMorphAgreement), "") << "offsets added after skinning look the same";
    }
    // Without weights, the bulge is gone.
    item.morphWeights = nullptr;
    DrawList plain;
    plain.add(item, drawable->primitiveCount());
    EXPECT_NE(test::disagreement(gpu, renderList(renderer, camera, plain), kMorphAgreement), "");
    EXPECT_EQ(renderer.statistics().morphInstances, 0u);
    // A non-finite weight is refused, naming the item.
    const std::vector<float> bad{NAN, 0.0f};
    item.morphWeights = bad.data();
    DrawList badList;
    badList.add(item, drawable->primitiveCount());
    renderer.beginFrame(camera);
    try {
        renderer.draw(badList);
        ADD_FAILURE() << "a NaN weight was drawn";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("morph weight 0 is not finite"), std::string::npos) << e.what();
    }
    renderer.endFrame();
}

// RobotExpressive rebuilt with one more clip, "face": its Idle clip's skeleton channels and constant
// morph weights `weights` (by channel name; the others 0).
std::shared_ptr<const ActorTemplate> withFace(const ActorTemplate& tmpl, const std::map<std::string, float>& weights) {
    ActorTemplateBuilder b(tmpl.name());
    for (const SkeletonNode& node : tmpl.nodes()) b.addNode(node);
    for (const VaLodLevel& level : tmpl.rootGeometry().levels()) b.rootGeometry().addLevel(level.maxDistance, level.drawable, level.skin);
    for (const Skin& skin : tmpl.skins()) b.addSkin(skin);
    std::vector<ClipChannel> channels;
    const int idle = tmpl.findClip("Idle");
    for (const ClipChannel& c : tmpl.clips()[static_cast<std::size_t>(idle < 0 ? 0 : idle)]->channels())
        if (c.target != ClipChannel::Target::MorphWeight) channels.push_back(c);
    for (std::size_t k = 0; k < tmpl.morphChannels().size(); ++k) {
        ClipChannel w;
        w.target = ClipChannel::Target::MorphWeight;
        w.node = static_cast<std::uint32_t>(k);
        w.times = {0.0f};
        const auto it = weights.find(tmpl.morphChannels()[k]);
        w.values = {it == weights.end() ? 0.0f : it->second};
        channels.push_back(w);
    }
    b.addClip(std::make_shared<const AnimationClip>("face", std::move(channels)));
    b.setSkeletonRootMargin(tmpl.skeletonRootMargin());
    return b.build();
}

// A camera 3 head radii from the robot's face (the items with morph targets), slightly from its left.
Camera faceCamera(testkit::Stage& stage, double time) {
    stage.frame(time, 0.0, 0.0);  // poses the actor
    BoundingSphere head;
    for (const DrawItem& item : stage.processor.drawList().items())
        if (item.drawable->morphTargetCount() > 0) head.expandBy(item.drawable->localBound().transformed(item.world.toMat4()));
    EXPECT_TRUE(head.valid()) << "no item with morph targets";
    const Vec3 centre = head.center();
    const double d = 3.0 * head.radius();
    Camera camera;
    camera.setPerspective(std::numbers::pi / 4.0, 1.0, 0.05 * d, 20.0 * d);
    camera.setLookAt(centre + d * Vec3(0.3, 0.15, 1.0), centre);
    return camera;
}

TEST_F(MorphRenderTest, RobotExpressiveFacesMatchTheirGoldensAndGpuAgreesWithCpu) {
    const auto robot = testkit::sharedCharacter("RobotExpressive.glb").primaryTemplate();
    ASSERT_TRUE(robot);
    ASSERT_EQ(robot->morphChannels().size(), 3u);
    struct Case {
        const char* golden;
        std::map<std::string, float> weights;
        std::uint64_t targetsRead;  // per frame: three head meshes times the non-zero weights
    };
    const Case cases[] = {{"robot_face_neutral", {}, 0},
                          {"robot_face_angry", {{"Angry", 1.0f}}, 3},
                          {"robot_face_surprised_sad", {{"Surprised", 0.5f}, {"Sad", 0.5f}}, 6}};
    const double time = 0.5;
    std::vector<Image> faces;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.golden);
        const auto tmpl = withFace(*robot, c.weights);
        testkit::Stage stage(tmpl, tmpl->findClip("face"));
        const Camera camera = faceCamera(stage, time);
        GlRenderer renderer(context);
        const Image gpu = stage.render(renderer, camera, time);
        EXPECT_EQ(renderer.statistics().morphTargetsRead, c.targetsRead);
        EXPECT_EQ(renderer.statistics().morphInstances, c.targetsRead ? 3u : 0u);
        EXPECT_GT(test::coveredPixels(gpu), std::size_t(kSize * kSize) / 10) << "the face is (nearly) out of the frame";
        RendererOptions cpuOptions = renderer.options();
        cpuOptions.forceCpuSkinning = true;
        renderer.setOptions(cpuOptions);
        const Image cpu = stage.render(renderer, camera, time);
        EXPECT_EQ(renderer.statistics().morphTargetsRead, c.targetsRead);
        const std::string apart = test::disagreement(gpu, cpu, kMorphAgreement);
        EXPECT_EQ(apart, "") << "GPU and CPU morphing disagree";
        if (!apart.empty()) test::writeOutput(cpu, std::string(c.golden) + "-cpu");
        const std::string failure = test::compareWithGolden(gpu, c.golden);
        EXPECT_TRUE(failure.empty()) << failure;
        if (c.targetsRead == 3) {
            // The offsets added to the placed vertices (world frame) instead of the mesh's own.
            renderer.setOptions(RendererOptions{});
            std::deque<std::shared_ptr<const MeshDrawable>> keep;
            DrawList wrong;
            for (const DrawItem& item : stage.processor.drawList().items()) {
                DrawItem w = item;
                if (item.morphWeights) {
                    const MeshData& mesh = static_cast<const MeshDrawable&>(*item.drawable).mesh();
                    auto moved = std::make_shared<MeshData>(mesh);
                    moved->morphTargets.clear();
                    const glm::dmat3 toMesh = glm::inverse(glm::dmat3(item.world.linear));
                    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
                        glm::dvec3 offset(0.0);
                        for (std::size_t k = 0; k < mesh.morphTargets.size(); ++k)
                            offset += double(item.morphWeights[k]) * glm::dvec3(mesh.morphTargets[k].positions[v]);
                        moved->positions[v] += glm::vec3(toMesh * offset);  // placed: world * p + offset
                    }
                    keep.push_back(test::drawable(moved));
                    w.drawable = keep.back().get();
                    w.morphWeights = nullptr;
                }
                wrong.add(w, w.drawable->primitiveCount());
            }
            EXPECT_NE(test::disagreement(gpu, renderList(renderer, camera, wrong), kMorphAgreement), "")
                << "offsets in the world frame look the same: the test cannot tell the order";
        }
        faces.push_back(gpu);
    }
    ASSERT_EQ(faces.size(), 3u);
    EXPECT_NE(test::disagreement(faces[0], faces[1], kMorphAgreement), "") << "Angry looks neutral";
    EXPECT_NE(test::disagreement(faces[1], faces[2], kMorphAgreement), "") << "Surprised + Sad looks Angry";
}

}  // namespace
}  // namespace throng
