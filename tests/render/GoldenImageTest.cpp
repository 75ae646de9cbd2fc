// Golden-image tests: small procedural scenes rendered headless and compared with PNGs in
// tests/render/golden/, made with OSMesa (llvmpipe); every scene is drawn through OSMesa and through
// EGL's surfaceless platform (the same rasteriser reached another way), both within the tolerance. THRONG_UPDATE_GOLDEN=1 rewrites the goldens (see
// RenderTestSupport.h); look at them before committing.
//
// Tolerance (GoldenTolerance): llvmpipe output is byte-stable for a given Mesa version, and on the
// Mesa these goldens were made with (22.3.6) the comparison is exact. Another Mesa or LLVM may round
// shading differently by a level or two and move a few edge pixels, so a frame passes when at most
// 0.5% of its pixels (96 of 160 x 120) differ by more than 8/255 in some channel and the PSNR is
// at least 35 dB. A wrong transform, colour, texture orientation or skinning changes far more.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "RenderTestSupport.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/EglContext.h"
#include "throng/render/OsMesaContext.h"
#include "throng/render/ProceduralMeshes.h"

namespace throng {
namespace {

using test::kHeight;
using test::kWidth;

// The headless contexts the goldens hold for.
enum class Headless { OsMesa, EglSurfaceless };

class GoldenImageTest : public ::testing::TestWithParam<Headless> {
protected:
    std::shared_ptr<GlContext> context = GetParam() == Headless::OsMesa
                                             ? std::shared_ptr<GlContext>(std::make_shared<OsMesaContext>(kWidth, kHeight))
                                             : std::make_shared<EglContext>(kWidth, kHeight, EglContext::Platform::Surfaceless);
};

glm::u8vec4 pixel(const Image& image, int x, int y) {
    const std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4];
    return {p[0], p[1], p[2], p[3]};
}

// A texture whose quadrants are red (top left), green (top right), blue (bottom left) and white,
// with a darker checker inside each: shows both orientation and filtering.
std::shared_ptr<Image> quadrantTexture() {
    auto image = makeCheckerImage(64, 8, {255, 255, 255, 255}, {170, 170, 170, 255});
    image->name = "quadrants";
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            std::uint8_t* p = &image->rgba[(static_cast<std::size_t>(y) * 64 + x) * 4];
            const bool right = x >= 32, bottom = y >= 32;
            if (!right && !bottom) p[1] = p[2] = 0;       // red
            else if (right && !bottom) p[0] = p[2] = 0;   // green
            else if (!right && bottom) p[0] = p[1] = 0;   // blue
        }
    return image;
}

TEST_P(GoldenImageTest, LitCube) {
    GlRenderer renderer(context);
    test::Scene scene;
    Mat4 world = glm::rotate(Mat4(1.0), 0.6, Vec3(0, 1, 0));
    world = glm::rotate(world, 0.35, Vec3(1, 0, 0));
    scene.add(test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.6f), glm::vec4(0.9f, 0.45f, 0.15f, 1.0f))), world);
    const Image image = test::renderFrame(renderer, test::makeCamera(Vec3(0, 0.6, 3.0), Vec3(0.0)), scene);
    EXPECT_EQ(renderer.statistics().drawCalls, 1u);
    EXPECT_EQ(renderer.statistics().triangles, 12u);
    EXPECT_GT(test::coveredPixels(image), 2000u);
    const std::string failure = test::compareWithGolden(image, "lit_cube");
    EXPECT_TRUE(failure.empty()) << failure;
}

TEST_P(GoldenImageTest, TexturedQuadIsUpright) {
    GlRenderer renderer(context);
    test::Scene scene;
    scene.add(test::drawable(makeQuad(1.6f, 1.2f, quadrantTexture())), Mat4(1.0));
    const Image image = test::renderFrame(renderer, test::makeCamera(Vec3(0, 0, 2.2), Vec3(0.0)), scene);
    // Independently of the golden: the image's top-left quadrant is red, bottom-right white.
    const glm::u8vec4 topLeft = pixel(image, kWidth / 2 - 20, kHeight / 2 - 15);
    const glm::u8vec4 topRight = pixel(image, kWidth / 2 + 20, kHeight / 2 - 15);
    const glm::u8vec4 bottomLeft = pixel(image, kWidth / 2 - 20, kHeight / 2 + 15);
    EXPECT_GT(topLeft.r, 100);
    EXPECT_LT(topLeft.g, 40);
    EXPECT_GT(topRight.g, 100);
    EXPECT_LT(topRight.r, 40);
    EXPECT_GT(bottomLeft.b, 100);
    EXPECT_LT(bottomLeft.r, 40);
    const std::string failure = test::compareWithGolden(image, "textured_quad");
    EXPECT_TRUE(failure.empty()) << failure;
}

TEST_P(GoldenImageTest, SkinnedTwoBoneCylinderBends) {
    GlRenderer renderer(context);
    SkinnedTubeOptions tube;  // two joints: the lower half follows joint 0, the upper half joint 1
    tube.color = glm::vec4(0.3f, 0.7f, 0.35f, 1.0f);
    std::vector<glm::mat4> palette;
    bendTubePalette(tube, 0.9f, palette);
    test::Scene scene;
    scene.add(test::drawable(makeSkinnedTube(tube)), glm::translate(Mat4(1.0), Vec3(0, -1, 0)), glm::vec4(1.0f),
              &palette);
    const Image image = test::renderFrame(renderer, test::makeCamera(Vec3(0, 0, 4.5), Vec3(0.0)), scene);
    EXPECT_EQ(renderer.statistics().gpuSkinnedVertices, 17u * 17u);
    EXPECT_EQ(renderer.statistics().cpuSkinnedVertices, 0u);
    // Bent about +Z, the upper half leans to -X: covered pixels of the top third lie well left of
    // those of the bottom third (the unbent lower half).
    const auto centroid = [&](int y0, int y1) {
        double sum = 0, n = 0;
        const int clearBlue = int(RendererOptions{}.clearColor.b * 255.0f + 0.5f);
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < kWidth; ++x)
                if (std::abs(pixel(image, x, y).b - clearBlue) > 10) sum += x, n += 1;
        return n > 0 ? sum / n : -1.0;
    };
    const double top = centroid(0, kHeight / 3), bottom = centroid(2 * kHeight / 3, kHeight);
    ASSERT_GE(top, 0.0);
    ASSERT_GE(bottom, 0.0);
    EXPECT_NEAR(bottom, kWidth / 2.0, 3.0);
    EXPECT_LT(top, bottom - 8.0);
    const std::string failure = test::compareWithGolden(image, "skinned_two_bone_cylinder");
    EXPECT_TRUE(failure.empty()) << failure;
}

TEST_P(GoldenImageTest, EightInfluenceTube) {
    GlRenderer renderer(context);
    SkinnedTubeOptions tube;
    tube.joints = 6;
    tube.influences = 8;
    tube.blend = 3.5f;  // each vertex feels up to 7 joints
    tube.ringsPerBand = 25;
    tube.color = glm::vec4(0.35f, 0.45f, 0.85f, 1.0f);
    std::vector<glm::mat4> palette;
    bendTubePalette(tube, 0.3f, palette, 0.2f);
    test::Scene scene;
    scene.add(test::drawable(makeSkinnedTube(tube)), glm::translate(Mat4(1.0), Vec3(0.4, -1, 0)), glm::vec4(1.0f),
              &palette);
    const Image image = test::renderFrame(renderer, test::makeCamera(Vec3(0, 0, 4.5), Vec3(0.0)), scene);
    EXPECT_GT(test::coveredPixels(image), 700u);
    const std::string failure = test::compareWithGolden(image, "eight_influence_tube");
    EXPECT_TRUE(failure.empty()) << failure;
}

TEST_P(GoldenImageTest, InstancedClonesInOneDrawCall) {
    GlRenderer renderer(context);
    auto box = test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.3f)));
    test::Scene scene;
    for (int i = 0; i < 9; ++i) {
        const int gx = i % 3 - 1, gy = i / 3 - 1;
        Mat4 world = glm::translate(Mat4(1.0), Vec3(0.9 * gx, 0.9 * gy, 0.0));
        world = glm::rotate(world, 0.3 * i, Vec3(0.3, 1.0, 0.1));
        const glm::vec4 tint(0.3f + 0.35f * float(gx + 1), 0.3f + 0.35f * float(gy + 1), 0.9f - 0.08f * float(i), 1.0f);
        scene.add(box, world, tint);
    }
    const Image image = test::renderFrame(renderer, test::makeCamera(Vec3(0, 0, 4.0), Vec3(0.0)), scene);
    EXPECT_EQ(renderer.statistics().drawCalls, 1u);
    EXPECT_EQ(renderer.statistics().instances, 9u);
    EXPECT_EQ(renderer.statistics().triangles, 9u * 12u);
    const std::string failure = test::compareWithGolden(image, "instanced_clones");
    EXPECT_TRUE(failure.empty()) << failure;
}

INSTANTIATE_TEST_SUITE_P(Contexts, GoldenImageTest, ::testing::Values(Headless::OsMesa, Headless::EglSurfaceless),
                         [](const auto& param) { return param.param == Headless::OsMesa ? "OsMesa" : "EglSurfaceless"; });

}  // namespace
}  // namespace throng
