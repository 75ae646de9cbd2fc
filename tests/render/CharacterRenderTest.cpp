// The renderer on real characters (issue 5): the glTF characters of the shared assets (CesiumMan,
// Fox, robot) loaded with loadCharacter, played by a KeyframeBehaviour, processed by ActorProcessor
// and drawn by GlRenderer, headless at 160 x 160.
//
//   * Golden images at fixed clip times and views, in tests/render/golden/character_*.png,
//     compared with the project's GoldenTolerance (see GoldenImageTest.cpp; at most 0.5% of the
//     pixels, 128 of 160 x 160, may differ by more than 8/255, PSNR >= 35 dB). Rewrite them with
//     THRONG_UPDATE_GOLDEN=1 as the other goldens.
//   * CPU and GPU skinning of the same posed CesiumMan give the same image within kSkinningAgreement.
//   * Skeletal LOD: a deactivated joint is drawn with its nearest active ancestor's skinning matrix.
//
// The camera is framed from the template's Sklsroot sphere (the Skeleton Root's position and the
// template's skeletonRootRadius), so a character modelled in centimetres (Fox) frames as one in
// metres.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>

#include "throng/testkit/CharacterStage.h"
#include "RenderTestSupport.h"
#include "throng/testkit/Assets.h"
#include "throng/testkit/Characters.h"
#include "throng/actors/Actor.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/render/CpuSkinning.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/OsMesaContext.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng {
namespace {

constexpr int kSize = testkit::kCharacterFrameSize;  // square frames

// CPU and GPU skinning compute the same linear-blend skinning (CpuSkinning.h); they differ only by
// float rounding (the vertex shader's order of operations is not skinMesh's), which may move a few
// edge pixels or shade them a level or two apart. A frame pair passes
// when at most 0.3% of the pixels (76 of 160 x 160) differ by more than 8/255 in some channel and the
// PSNR is at least 40 dB. One wrong joint or a pose 0.1 s apart fails it (checked below). Measured
// with Mesa 22.3.6 llvmpipe: no pixel over the threshold, largest difference 1/255, PSNR 74.7 dB.
const test::GoldenTolerance kSkinningAgreement{8, 0.003, 40.0};

// Each file is loaded once for the whole test program.
const CharacterAsset& asset(const std::string& file) { return testkit::sharedCharacter(file); }

using testkit::Stage;

int clipIndex(const ActorTemplate& tmpl, const std::string& name) {
    return name.empty() ? 0 : tmpl.findClip(name);
}

std::size_t skinnedVertices(const ActorTemplate& tmpl) {
    std::size_t n = 0;
    for (const VaLodLevel& level : tmpl.rootGeometry().levels())
        if (level.skin >= 0)
            if (const auto* mesh = dynamic_cast<const MeshDrawable*>(level.drawable.get())) n += mesh->mesh().vertexCount();
    return n;
}

class CharacterRenderTest : public ::testing::Test {
protected:
    std::shared_ptr<OsMesaContext> context = std::make_shared<OsMesaContext>(kSize, kSize);
};

TEST_F(CharacterRenderTest, GoldenImagesOfLoadedCharacters) {
    for (const testkit::CharacterGoldenCase& c : testkit::kCharacterGoldenCases) {
        SCOPED_TRACE(c.golden);
        ASSERT_TRUE(std::filesystem::exists(testkit::characterPath(c.file))) << testkit::characterPath(c.file) << " is missing";
        const auto tmpl = asset(c.file).primaryTemplate();
        ASSERT_TRUE(tmpl);
        const int clip = clipIndex(*tmpl, c.clip);
        ASSERT_GE(clip, 0) << "no clip " << c.clip;
        Stage stage(tmpl, clip);
        GlRenderer renderer(context);
        const double deg = std::numbers::pi / 180.0;
        const Camera camera = stage.frame(c.time, c.azimuthDeg * deg, c.elevationDeg * deg);
        const Image image = stage.render(renderer, camera, c.time);
        // Independently of the golden: the whole skinned mesh went through the GPU path, and the
        // character covers a fair part of the frame without filling it.
        EXPECT_EQ(renderer.statistics().gpuSkinnedVertices, skinnedVertices(*tmpl));
        EXPECT_GT(skinnedVertices(*tmpl), 0u);
        EXPECT_EQ(renderer.statistics().cpuSkinnedVertices, 0u);
        const std::size_t covered = test::coveredPixels(image);
        EXPECT_GT(covered, std::size_t(kSize * kSize) / 25) << "the character is (nearly) out of the frame";
        EXPECT_LT(covered, std::size_t(kSize * kSize) * 3 / 4) << "the camera is inside the character";
        // The clip is played: 0.2 s later the pose, hence the frame, is another.
        const Image later = stage.render(renderer, camera, c.time + 0.2);
        const testkit::ImageDifference moved = testkit::compareImages(image, later, 8);
        EXPECT_GT(moved.pixelsOverThreshold, std::size_t(kSize * kSize) / 200) << "the pose does not change with time";
        const std::string failure = test::compareWithGolden(image, c.golden);
        EXPECT_TRUE(failure.empty()) << failure;
    }
}

using test::disagreement;

TEST_F(CharacterRenderTest, CpuAndGpuSkinningAgreeOnCesiumMan) {
    const auto tmpl = asset("CesiumMan.glb").primaryTemplate();
    ASSERT_TRUE(tmpl);
    Stage stage(tmpl, 0);
    const double time = 0.7;
    const Camera camera = stage.frame(time, 0.5, 0.15);
    GlRenderer renderer(context);
    const Image gpu = stage.render(renderer, camera, time);
    EXPECT_EQ(renderer.statistics().gpuSkinnedVertices, skinnedVertices(*tmpl));
    EXPECT_EQ(renderer.statistics().cpuSkinnedVertices, 0u);
    RendererOptions cpuOptions = renderer.options();
    cpuOptions.forceCpuSkinning = true;
    renderer.setOptions(cpuOptions);
    const Image cpu = stage.render(renderer, camera, time);
    EXPECT_EQ(renderer.statistics().cpuSkinnedVertices, skinnedVertices(*tmpl));
    EXPECT_EQ(renderer.statistics().gpuSkinnedVertices, 0u);
    EXPECT_GT(test::coveredPixels(cpu), std::size_t(kSize * kSize) / 25);
    const testkit::ImageDifference d = testkit::compareImages(cpu, gpu, kSkinningAgreement.threshold);
    RecordProperty("pixels_over_threshold", std::to_string(d.pixelsOverThreshold));
    RecordProperty("psnr_db", std::to_string(d.psnr));
    RecordProperty("max_channel_difference", std::to_string(d.maxChannelDifference));
    const std::string failure = disagreement(cpu, gpu, kSkinningAgreement);
    EXPECT_TRUE(failure.empty()) << "CPU and GPU skinning disagree: " << failure;
    if (!failure.empty()) {
        test::writeOutput(cpu, "cesium_man_cpu_skinning");
        test::writeOutput(gpu, "cesium_man_gpu_skinning");
    }
    // The tolerance is tight enough to see a pose 0.1 s apart.
    const Image later = stage.render(renderer, camera, time + 0.1);
    EXPECT_FALSE(disagreement(later, gpu, kSkinningAgreement).empty()) << "the agreement tolerance is too loose";
}

// `tmpl` rebuilt with the subtree of node `first` deactivated beyond `distance` (loaded templates keep
// every node active at any distance).
std::shared_ptr<const ActorTemplate> withDeactivatedSubtree(const ActorTemplate& tmpl, int first, double distance) {
    ActorTemplateBuilder b(tmpl.name() + "-lod");
    for (std::size_t i = 0; i < tmpl.nodeCount(); ++i) {
        SkeletonNode node = tmpl.nodes()[i];
        if (i >= std::size_t(first) && i < tmpl.subtreeEnd(std::size_t(first))) node.deactivationDistance = distance;
        b.addNode(node);
    }
    for (const VaLodLevel& level : tmpl.rootGeometry().levels()) b.rootGeometry().addLevel(level.maxDistance, level.drawable, level.skin);
    for (const Skin& skin : tmpl.skins()) b.addSkin(skin);
    for (const auto& clip : tmpl.clips()) b.addClip(clip);
    b.setSkeletonRootMargin(tmpl.skeletonRootMargin());
    return b.build();
}

// Skeletal LOD in rendering, on CesiumMan: with the right leg from the knee down deactivated, the
// knee and ankle joints are drawn with the hip's (their nearest active ancestor's) skinning matrix:
// the palette says so, and the frame is the one drawn from the full-detail palette with those
// joints' matrices replaced by the hip's.
TEST_F(CharacterRenderTest, DeactivatedJointsUseTheirNearestActiveAncestorsSkinningMatrix) {
    const auto loaded = asset("CesiumMan.glb").primaryTemplate();
    ASSERT_TRUE(loaded);
    const int knee = loaded->findNode("leg_joint_R_2");
    ASSERT_GE(knee, 0);
    const int hip = loaded->nodes()[std::size_t(knee)].parent;
    ASSERT_GE(hip, 0);
    const auto tmpl = withDeactivatedSubtree(*loaded, knee, 8.0);
    ASSERT_EQ(tmpl->skins().size(), 1u);
    const Skin& skin = tmpl->skins()[0];
    const auto jointOf = [&](std::size_t node) {
        for (std::size_t k = 0; k < skin.joints.size(); ++k)
            if (skin.joints[k] == node) return int(k);
        return -1;
    };
    const int hipJoint = jointOf(std::size_t(hip));
    ASSERT_GE(hipJoint, 0);
    std::vector<int> deactivated;  // skin joints in the knee's subtree
    for (std::size_t n = std::size_t(knee); n < tmpl->subtreeEnd(std::size_t(knee)); ++n)
        if (jointOf(n) >= 0) deactivated.push_back(jointOf(n));
    ASSERT_GE(deactivated.size(), 2u);  // knee, ankle (and toe)

    Stage stage(tmpl, 0);
    const double time = 0.55;  // mid-stride: the right knee is bent
    const Camera camera = stage.frame(time, 1.4, 0.1);
    GlRenderer renderer(context);
    // The camera is a few metres away (1.6 Sklsroot radii): at LOD scale 1 every node is active, at
    // 10 the knee's subtree (deactivated beyond 8 m) is not; the checks below fail otherwise.
    stage.processor.setLodScale(1.0);
    const Image full = stage.render(renderer, camera, time);
    ASSERT_EQ(stage.processor.drawList().size(), 1u);
    DrawItem fullItem = stage.processor.drawList().items()[0];
    ASSERT_EQ(fullItem.skinPaletteSize, skin.joints.size());
    const std::vector<glm::mat4> fullPalette(fullItem.skinPalette, fullItem.skinPalette + fullItem.skinPaletteSize);

    stage.processor.setLodScale(10.0);
    const Image lod = stage.render(renderer, camera, time);
    ASSERT_EQ(stage.processor.drawList().size(), 1u);
    const DrawItem& lodItem = stage.processor.drawList().items()[0];
    ASSERT_EQ(lodItem.skinPaletteSize, skin.joints.size());
    std::vector<glm::mat4> expected = fullPalette;
    for (int k : deactivated) expected[std::size_t(k)] = fullPalette[std::size_t(hipJoint)];
    for (std::size_t k = 0; k < expected.size(); ++k)
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                EXPECT_NEAR(lodItem.skinPalette[k][c][r], expected[k][c][r], 1e-5f) << "joint " << k;

    // The leg visibly changes: deactivation is not a no-op.
    EXPECT_GT(testkit::compareImages(full, lod, 8).pixelsOverThreshold, 30u) << "deactivating the knee did not move the leg";
    // And the renderer draws exactly what the ancestor's matrix gives.
    fullItem.skinPalette = expected.data();
    const Image substituted = testkit::drawAlone(renderer, camera, fullItem);
    const std::string failure = disagreement(lod, substituted, {0, 0.0, 0.0});
    EXPECT_TRUE(failure.empty()) << failure;
    if (!failure.empty()) {
        test::writeOutput(lod, "cesium_man_lod");
        test::writeOutput(substituted, "cesium_man_lod_expected");
    }
}

}  // namespace
}  // namespace throng
