// Dynamic resolution (CrowdRendererOptions::renderScale, ScaledFrame): a frame drawn at a fraction
// of the context's size comes back at the full size, close to the full-resolution frame but not
// equal to it, with the text overlay at full resolution; bad scales are refused by name.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "RenderTestSupport.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/render/GlContext.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/render/ProceduralMeshes.h"
#include "throng/render/ScaledFrame.h"
#include "throng/scenegraph/MeshShapes.h"

using namespace throng;

namespace {

// A checker-textured quad and a box: edges and texture detail that a lower resolution blurs.
test::Scene checkerScene() {
    test::Scene scene;
    static const auto quad = test::drawable(makeQuad(2.0f, 2.0f, makeCheckerImage(64, 16, {250, 250, 250, 255}, {20, 40, 160, 255})));
    static const auto box = test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.3f), glm::vec4(0.8f, 0.3f, 0.2f, 1.0f)));
    scene.add(quad, Mat4(1.0));
    scene.add(box, glm::translate(Mat4(1.0), Vec3(0.4, 0.3, 0.5)));
    return scene;
}

Image drawAt(float scale, const std::string& text = {}, CrowdRenderStatistics* stats = nullptr) {
    auto context = createContext({.width = test::kWidth, .height = test::kHeight});
    CrowdRendererOptions options;
    options.renderScale = scale;
    CrowdRenderer renderer(context, options);
    renderer.setOverlayText(text);
    const test::Scene scene = checkerScene();
    renderer.beginFrame(test::makeCamera(Vec3(0.3, -0.4, 3.0), Vec3(0.0)));
    renderer.draw(scene.list());
    renderer.endFrame();
    if (stats) *stats = renderer.statistics();
    return renderer.readFrame();
}

}  // namespace

TEST(ScaledFrame, AHalfResolutionFrameComesBackFullSizeCloseToTheFullFrame) {
    CrowdRenderStatistics full{}, half{};
    const Image reference = drawAt(1.0f, {}, &full);
    const Image scaled = drawAt(0.5f, {}, &half);
    EXPECT_EQ(full.renderWidth, test::kWidth);
    EXPECT_EQ(half.renderWidth, test::kWidth / 2);
    EXPECT_EQ(half.renderHeight, test::kHeight / 2);
    ASSERT_EQ(scaled.width, reference.width);
    ASSERT_EQ(scaled.height, reference.height);
    const testkit::ImageDifference d = testkit::compareImages(reference, scaled, 8);
    test::writeOutput(scaled, "scaled-frame-half");
    EXPECT_GT(d.psnr, 18.0) << "the same picture, blurred";
    EXPECT_GT(d.pixelsOverThreshold, 0u) << "a lower resolution must cost something";
    EXPECT_LT(d.fractionOverThreshold, 0.5);
    // Scale 1 draws exactly what a renderer without the option draws.
    EXPECT_EQ(testkit::compareImages(reference, drawAt(1.0f), 0).pixelsOverThreshold, 0u);
}

TEST(ScaledFrame, TheOverlayIsDrawnAtFullResolutionOverTheScaledFrame) {
    // Text drawn at full resolution is sharp: its pixels equal between the scaled and full frames
    // where the panel covers the scene, while the scene elsewhere differs.
    const Image full = drawAt(1.0f, "Throng 42");
    const Image half = drawAt(0.25f, "Throng 42");
    int textPixels = 0, sameTextPixels = 0;
    for (int y = 14; y < 14 + 12; ++y)
        for (int x = 14; x < 14 + 9 * 6; ++x) {
            const std::uint8_t* a = &full.rgba[std::size_t(y * full.width + x) * 4];
            const std::uint8_t* b = &half.rgba[std::size_t(y * half.width + x) * 4];
            if (a[0] < 200 || a[1] < 200 || a[2] < 200) continue;  // a letter's pixel is near white
            ++textPixels;
            sameTextPixels += a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
        }
    ASSERT_GT(textPixels, 20) << "letters drawn";
    EXPECT_EQ(sameTextPixels, textPixels);
}

TEST(ScaledFrame, BadScalesAreRefusedByName) {
    auto context = createContext({.width = 32, .height = 32});
    for (float bad : {0.0f, -0.5f, 1.5f, std::numeric_limits<float>::quiet_NaN()}) {
        CrowdRendererOptions options;
        options.renderScale = bad;
        try {
            CrowdRenderer renderer(context, options);
            ADD_FAILURE() << "scale " << bad << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("render scale"), std::string::npos) << e.what();
        }
    }
    CrowdRenderer renderer(context);
    EXPECT_THROW(renderer.setRenderScale(0.0f), std::invalid_argument);
    ScaledFrame frame(*context);
    EXPECT_THROW(frame.begin(1.0f), std::invalid_argument);
    EXPECT_THROW(frame.end(), std::logic_error);
    frame.begin(0.5f);
    EXPECT_EQ(context->drawTarget().width, 16);
    EXPECT_THROW(frame.begin(0.5f), std::logic_error);
    frame.end();
    EXPECT_EQ(context->drawTarget().width, 32) << "drawing given back to the context";
}
