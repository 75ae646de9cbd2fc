// CPU and GPU linear-blend skinning compute the same thing: vertex by vertex (the GPU's skinned
// vertices read back by transform feedback) and image by image (a frame drawn with each path).
//
// Vertex tolerance: both paths blend the same normalised weights in the same order in float, but
// the GPU may fuse multiply-adds and evaluate in another order, so results differ by rounding
// only: a few ulps of the largest coordinates (ulp(2 m) = 2.4e-7 m). We allow 2e-6 m on
// positions (about 8 ulps, 1e-6 of the 2 m tube) and 2e-6 on unit normals; a wrong joint or weight
// moves vertices by centimetres.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "RenderTestSupport.h"
#include "throng/render/CpuSkinning.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/GpuSkinner.h"
#include "throng/render/OsMesaContext.h"
#include "throng/render/ProceduralMeshes.h"

namespace throng {
namespace {

constexpr float kPositionTolerance = 2e-6f;
constexpr float kNormalTolerance = 2e-6f;

struct Skinned {
    std::vector<glm::vec3> positions, normals;
};

Skinned cpuSkin(const MeshData& mesh, const std::vector<glm::mat4>& palette) {
    Skinned s{std::vector<glm::vec3>(mesh.vertexCount()), std::vector<glm::vec3>(mesh.vertexCount())};
    skinMesh(mesh, palette, s.positions, s.normals);
    return s;
}

Skinned gpuSkin(GpuSkinner& skinner, const MeshData& mesh, const std::vector<glm::mat4>& palette) {
    Skinned s{std::vector<glm::vec3>(mesh.vertexCount()), std::vector<glm::vec3>(mesh.vertexCount())};
    skinner.skin(mesh, palette, s.positions, s.normals);
    return s;
}

float maxDistance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
    return worst;
}

// Checks CPU against GPU within the tolerances and records the measured gaps in the test report.
void expectAgreement(const Skinned& cpu, const Skinned& gpu) {
    const float positions = maxDistance(cpu.positions, gpu.positions), normals = maxDistance(cpu.normals, gpu.normals);
    EXPECT_LE(positions, kPositionTolerance);
    EXPECT_LE(normals, kNormalTolerance);
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", double(positions));
    ::testing::Test::RecordProperty("max_position_gap_m", text);
    std::snprintf(text, sizeof text, "%.3g", double(normals));
    ::testing::Test::RecordProperty("max_normal_gap", text);
}

float maxMovement(const MeshData& mesh, const std::vector<glm::vec3>& skinned) {
    return maxDistance(mesh.positions, skinned);
}

class SkinningTest : public ::testing::Test {
protected:
    std::shared_ptr<OsMesaContext> context = std::make_shared<OsMesaContext>(test::kWidth, test::kHeight);
    GpuSkinner skinner{context};
};

TEST_F(SkinningTest, CpuAndGpuVerticesAgreeWithFourInfluences) {
    SkinnedTubeOptions tube;
    tube.joints = 7;
    tube.blend = 1.7f;  // up to 4 joints per vertex
    tube.bands = 3;
    tube.ringsPerBand = 9;
    const auto mesh = makeSkinnedTube(tube);
    std::vector<glm::mat4> palette;
    bendTubePalette(tube, 0.45f, palette, 0.3f);
    const Skinned cpu = cpuSkin(*mesh, palette), gpu = gpuSkin(skinner, *mesh, palette);
    EXPECT_GT(maxMovement(*mesh, cpu.positions), 0.5f);  // the pose really moves the mesh
    expectAgreement(cpu, gpu);
}

TEST_F(SkinningTest, CpuAndGpuVerticesAgreeWithEightInfluences) {
    SkinnedTubeOptions tube;
    tube.joints = 9;
    tube.influences = 8;
    tube.blend = 3.6f;  // up to 8 joints per vertex
    const auto mesh = makeSkinnedTube(tube);
    ASSERT_EQ(mesh->influenceCount(), 8);
    std::vector<glm::mat4> palette;
    bendTubePalette(tube, 0.25f, palette, -0.4f);
    const Skinned cpu = cpuSkin(*mesh, palette), gpu = gpuSkin(skinner, *mesh, palette);
    EXPECT_GT(maxMovement(*mesh, cpu.positions), 0.5f);
    expectAgreement(cpu, gpu);
}

TEST_F(SkinningTest, CesiumManSizedMeshAgrees) {
    const SkinnedTubeOptions tube = cesiumManSizedTube();
    const auto mesh = makeSkinnedTube(tube);
    EXPECT_EQ(mesh->vertexCount(), 3264u);
    EXPECT_EQ(mesh->triangleCount(), 4608u);
    std::vector<glm::mat4> palette;
    bendTubePalette(tube, 0.12f, palette, 0.05f);
    const Skinned cpu = cpuSkin(*mesh, palette), gpu = gpuSkin(skinner, *mesh, palette);
    expectAgreement(cpu, gpu);
}

TEST_F(SkinningTest, IdentityPaletteGivesTheBindPose) {
    SkinnedTubeOptions tube;
    tube.joints = 4;
    const auto mesh = makeSkinnedTube(tube);
    const std::vector<glm::mat4> identity(4, glm::mat4(1.0f));
    const Skinned cpu = cpuSkin(*mesh, identity), gpu = gpuSkin(skinner, *mesh, identity);
    EXPECT_LE(maxDistance(cpu.positions, mesh->positions), 1e-6f);
    EXPECT_LE(maxDistance(gpu.positions, mesh->positions), 1e-6f);
}

TEST_F(SkinningTest, WeightsNotSummingToOneAreNormalised) {
    SkinnedTubeOptions tube;
    tube.joints = 3;
    const auto mesh = makeSkinnedTube(tube);
    auto scaled = std::make_shared<MeshData>(*mesh);
    for (std::size_t v = 0; v < scaled->vertexCount(); ++v) scaled->weights0[v] *= 0.3f + 0.01f * float(v % 50);
    std::vector<glm::mat4> palette;
    bendTubePalette(tube, 0.7f, palette);
    const Skinned reference = cpuSkin(*mesh, palette);
    const Skinned cpu = cpuSkin(*scaled, palette), gpu = gpuSkin(skinner, *scaled, palette);
    EXPECT_LE(maxDistance(cpu.positions, reference.positions), kPositionTolerance);
    EXPECT_LE(maxDistance(gpu.positions, reference.positions), kPositionTolerance);
}

TEST_F(SkinningTest, VertexWithoutWeightKeepsItsBindPosition) {
    SkinnedTubeOptions tube;
    tube.joints = 2;
    auto mesh = makeSkinnedTube(tube);
    const std::size_t last = mesh->vertexCount() - 1;  // top ring: fully on joint 1
    mesh->weights0[last] = glm::vec4(0.0f);
    std::vector<glm::mat4> palette;
    bendTubePalette(tube, 1.0f, palette);
    const Skinned cpu = cpuSkin(*mesh, palette), gpu = gpuSkin(skinner, *mesh, palette);
    EXPECT_EQ(cpu.positions[last], mesh->positions[last]);
    EXPECT_LE(glm::length(gpu.positions[last] - mesh->positions[last]), 1e-6f);
    EXPECT_GT(glm::length(cpu.positions[last - 1] - mesh->positions[last - 1]), 0.3f);  // its neighbour moved
}

TEST_F(SkinningTest, ZeroWeightJointOutsideThePaletteIsIgnored) {
    SkinnedTubeOptions tube;
    tube.joints = 2;
    auto mesh = makeSkinnedTube(tube);
    for (std::size_t v = 0; v < mesh->vertexCount(); ++v) {
        mesh->joints0[v].w = 999;  // unused slot pointing nowhere, as some exporters write
        mesh->weights0[v].w = 0.0f;
    }
    EXPECT_EQ(requiredPaletteSize(*mesh), 2u);
    std::vector<glm::mat4> palette;
    bendTubePalette(tube, 0.5f, palette);
    const Skinned cpu = cpuSkin(*mesh, palette), gpu = gpuSkin(skinner, *mesh, palette);
    EXPECT_LE(maxDistance(cpu.positions, gpu.positions), kPositionTolerance);
}

TEST_F(SkinningTest, ShortPaletteIsAnErrorOnBothPaths) {
    SkinnedTubeOptions tube;
    tube.joints = 3;
    tube.blend = 1.0f;
    const auto mesh = makeSkinnedTube(tube);
    mesh->name = "three-joint tube";
    EXPECT_EQ(requiredPaletteSize(*mesh), 3u);
    const std::vector<glm::mat4> shortPalette(2, glm::mat4(1.0f));
    std::vector<glm::vec3> positions(mesh->vertexCount());
    for (const bool gpu : {false, true}) {
        try {
            if (gpu) skinner.skin(*mesh, shortPalette, positions, {});
            else skinMesh(*mesh, shortPalette, positions, {});
            ADD_FAILURE() << "a palette of 2 for joints up to 2 was accepted (gpu=" << gpu << ")";
        } catch (const std::invalid_argument& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("three-joint tube"), std::string::npos) << what;
            EXPECT_NE(what.find("palette of 3"), std::string::npos) << what;
            EXPECT_NE(what.find("has 2"), std::string::npos) << what;
        }
    }
}

TEST_F(SkinningTest, BadOutputsAndUnskinnedMeshesAreErrors) {
    const auto box = makeBox("box", glm::vec3(0.0f), glm::vec3(1.0f));
    std::vector<glm::vec3> out(box->vertexCount());
    const std::vector<glm::mat4> palette(1, glm::mat4(1.0f));
    EXPECT_THROW(skinMesh(*box, palette, out, {}), std::invalid_argument);
    EXPECT_THROW(skinner.skin(*box, palette, out, {}), std::invalid_argument);
    SkinnedTubeOptions tube;
    const auto mesh = makeSkinnedTube(tube);
    std::vector<glm::vec3> tooFew(mesh->vertexCount() - 1);
    EXPECT_THROW(skinMesh(*mesh, palette, tooFew, {}), std::invalid_argument);
    EXPECT_THROW(skinner.skin(*mesh, palette, tooFew, {}), std::invalid_argument);
    auto nanWeight = std::make_shared<MeshData>(*mesh);
    nanWeight->weights0[3].x = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(requiredPaletteSize(*nanWeight), std::invalid_argument);
}

// A frame drawn with GPU skinning and one drawn with CPU skinning. Their vertices agree to a few
// ulps (above), which can still move an edge across a pixel centre: allow 0.2% of the pixels to
// differ by more than 8/255 (in practice the frames are identical or nearly so).
TEST_F(SkinningTest, CpuAndGpuSkinnedFramesAgree) {
    test::Scene scene;
    SkinnedTubeOptions four;
    four.joints = 5;
    four.blend = 1.6f;
    four.color = glm::vec4(0.8f, 0.4f, 0.3f, 1.0f);
    SkinnedTubeOptions eight = four;
    eight.influences = 8;
    eight.blend = 3.0f;
    eight.color = glm::vec4(0.3f, 0.5f, 0.8f, 1.0f);
    const auto fourMesh = test::drawable(makeSkinnedTube(four));
    const auto eightMesh = test::drawable(makeSkinnedTube(eight));
    std::vector<glm::mat4> palette;
    for (int i = 0; i < 6; ++i) {
        const SkinnedTubeOptions& o = i % 2 ? eight : four;
        bendTubePalette(o, 0.15f + 0.08f * float(i), palette, 0.2f * float(i - 3));
        scene.add(i % 2 ? eightMesh : fourMesh, glm::translate(Mat4(1.0), Vec3(-1.5 + 0.6 * i, -1.0, -0.3 * (i % 3))),
                  glm::vec4(1.0f), &palette);
    }
    const Camera camera = test::makeCamera(Vec3(0, 0.2, 4.5), Vec3(0.0));
    GlRenderer renderer(context);
    const Image gpuFrame = test::renderFrame(renderer, camera, scene);
    EXPECT_EQ(renderer.statistics().gpuSkinnedVertices, 6u * 17u * 17u);
    EXPECT_EQ(renderer.statistics().cpuSkinnedVertices, 0u);
    RendererOptions options;
    options.forceCpuSkinning = true;
    renderer.setOptions(options);
    const Image cpuFrame = test::renderFrame(renderer, camera, scene);
    EXPECT_EQ(renderer.statistics().cpuSkinnedVertices, 6u * 17u * 17u);
    EXPECT_EQ(renderer.statistics().gpuSkinnedVertices, 0u);
    EXPECT_EQ(renderer.statistics().drawCalls, 6u);
    EXPECT_GT(test::coveredPixels(gpuFrame), 2000u);
    const testkit::ImageDifference d = testkit::compareImages(gpuFrame, cpuFrame, 8);
    EXPECT_LE(d.fractionOverThreshold, 0.002) << "max difference " << d.maxChannelDifference;
    if (d.maxChannelDifference > 0) {
        test::writeOutput(gpuFrame, "skinning-gpu");
        test::writeOutput(cpuFrame, "skinning-cpu");
    }
    RecordProperty("max_channel_difference", d.maxChannelDifference);
}

}  // namespace
}  // namespace throng
