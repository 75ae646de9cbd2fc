// GlRenderer behaviour: instancing, camera-relative rendering far from the origin, statistics,
// resource caching, options, integration with TraditionalProcessor, and clear errors on bad input.

#include <gtest/gtest.h>

#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "RenderTestSupport.h"
#include "throng/testkit/Errors.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/OsMesaContext.h"
#include "throng/render/ProceduralMeshes.h"
#include "throng/render/ShaderProgram.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/TraditionalProcessor.h"
#include "throng/scenegraph/Transform.h"

namespace throng {
namespace {

using test::kHeight;
using test::kWidth;

class RendererTest : public ::testing::Test {
protected:
    std::shared_ptr<OsMesaContext> context = std::make_shared<OsMesaContext>(kWidth, kHeight);
};

template <class F>
std::string errorOf(F&& f) { return testkit::errorOf<std::exception>(std::forward<F>(f)); }

// Boxes and skinned tubes of two meshes, interleaved in the list, placed around `origin`.
void buildMixedScene(test::Scene& scene, const Vec3& origin) {
    static const auto box = test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.25f), glm::vec4(0.8f, 0.7f, 0.3f, 1.0f)));
    static const auto cube = test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.15f), glm::vec4(0.3f, 0.7f, 0.8f, 1.0f)));
    SkinnedTubeOptions options;
    options.joints = 3;
    options.height = 1.2f;
    options.radius = 0.12f;
    static const auto tube = test::drawable(makeSkinnedTube(options));
    std::vector<glm::mat4> palette;
    for (int i = 0; i < 12; ++i) {
        const Vec3 at = origin + Vec3(-1.6 + 0.3 * i, (i % 3) * 0.5 - 0.5, -0.25 * (i % 4));
        Mat4 world = glm::rotate(glm::translate(Mat4(1.0), at), 0.4 * i, Vec3(0.2, 1.0, 0.3));
        const glm::vec4 tint(1.0f - 0.05f * float(i), 0.6f + 0.03f * float(i), 1.0f, 1.0f);
        switch (i % 3) {
            case 0: scene.add(box, world, tint); break;
            case 1: scene.add(cube, world, tint); break;
            default:
                bendTubePalette(options, 0.2f * float(i % 5), palette);
                scene.add(tube, glm::translate(Mat4(1.0), at), tint, &palette);
        }
    }
}

TEST_F(RendererTest, InstancedAndSeparateDrawsGiveIdenticalImages) {
    test::Scene scene;
    buildMixedScene(scene, Vec3(0.0));
    const Camera camera = test::makeCamera(Vec3(0, 0.5, 4.0), Vec3(0.0));
    GlRenderer renderer(context);
    const Image instanced = test::renderFrame(renderer, camera, scene);
    EXPECT_EQ(renderer.statistics().drawCalls, 3u);  // one per mesh
    EXPECT_EQ(renderer.statistics().instances, 12u);
    RendererOptions options;
    options.instancing = false;
    renderer.setOptions(options);
    const Image separate = test::renderFrame(renderer, camera, scene);
    EXPECT_EQ(renderer.statistics().drawCalls, 12u);
    EXPECT_EQ(renderer.statistics().instances, 12u);
    EXPECT_GT(test::coveredPixels(instanced), 1500u);
    const testkit::ImageDifference d = testkit::compareImages(instanced, separate);
    EXPECT_EQ(d.maxChannelDifference, 0);
}

// The same scene and camera 10^7 m from the origin. In float, positions there are quantised to
// 1 m (the scene would collapse); the renderer subtracts the eye in double, so the image must be
// the one drawn at the origin (identical here: every eye-relative matrix rounds to the same float).
TEST_F(RendererTest, CameraRelativeRenderingFarFromTheOrigin) {
    const Vec3 far(1.0e7, 250.0, -1.0e7);
    ASSERT_EQ(static_cast<float>(far.x + 0.3), static_cast<float>(far.x));  // float alone cannot tell 0.3 m apart
    GlRenderer renderer(context);
    test::Scene near, distant;
    buildMixedScene(near, Vec3(0.0));
    buildMixedScene(distant, far);
    const Image a = test::renderFrame(renderer, test::makeCamera(Vec3(0, 0.5, 4.0), Vec3(0.0)), near);
    const Image b = test::renderFrame(renderer, test::makeCamera(far + Vec3(0, 0.5, 4.0), far), distant);
    const testkit::ImageDifference d = testkit::compareImages(a, b, 2);
    EXPECT_LE(d.maxChannelDifference, 2);
    EXPECT_EQ(d.pixelsOverThreshold, 0u);
    EXPECT_GT(test::coveredPixels(b), 1500u);
}

// A mirroring world matrix (negative determinant) turns the mesh's winding around on screen: the
// renderer must flip the front face for it, or back-face culling shows the box inside out. Seen
// from the x = 0 plane, a box mirrored in x looks exactly like the box.
TEST_F(RendererTest, MirroredItemsAreNotDrawnInsideOut) {
    GlRenderer renderer(context);
    const auto box = test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.5f, 0.4f, 0.3f), glm::vec4(0.8f, 0.6f, 0.3f, 1.0f)));
    const Mat4 tilt = glm::rotate(Mat4(1.0), 0.4, Vec3(1, 0, 0));
    test::Scene plain, mirrored, both;
    plain.add(box, tilt);
    mirrored.add(box, glm::scale(Mat4(1.0), Vec3(-1, 1, 1)) * tilt);
    const Camera camera = test::makeCamera(Vec3(0, 1, 3), Vec3(0.0));
    const Image a = test::renderFrame(renderer, camera, plain);
    const Image b = test::renderFrame(renderer, camera, mirrored);
    EXPECT_GT(test::coveredPixels(a), 1500u);
    EXPECT_EQ(test::coveredPixels(a), test::coveredPixels(b));
    EXPECT_LE(testkit::compareImages(a, b, 8).fractionOverThreshold, 0.001);
    // Mixed in one list, with instancing: mirrored items get their own draw call.
    both.add(box, glm::translate(Mat4(1.0), Vec3(-0.7, 0, 0)) * tilt);
    both.add(box, glm::translate(Mat4(1.0), Vec3(0.7, 0, 0)) * glm::scale(Mat4(1.0), Vec3(-1, 1, 1)) * tilt);
    test::renderFrame(renderer, camera, both);
    EXPECT_EQ(renderer.statistics().drawCalls, 2u);
}

// Probes leave part of DRAW's work out, to find where its time goes; fragment counts say how much
// was rasterised. Two boxes, the nearer hiding part of the farther: drawn front to back, exactly the
// covered pixels pass the depth test; with no depth rejection every fragment of both boxes does
// (the sum of each drawn alone); set-up only passes at most the 8 x 8 scissor; depth only writes no
// colour; one colour passes the same fragments, shaded otherwise; and the next plain frame is the
// picture drawn before any probe.
TEST_F(RendererTest, ProbesLeaveWorkOutAndFragmentCountsAddUp) {
    const auto nearBox = test::drawable(makeBox("near", glm::vec3(0.0f), glm::vec3(0.4f), glm::vec4(0.8f, 0.6f, 0.3f, 1.0f)));
    const auto farBox = test::drawable(makeBox("far", glm::vec3(0.0f), glm::vec3(0.7f), glm::vec4(0.3f, 0.6f, 0.8f, 1.0f)));
    const Mat4 nearAt = glm::translate(Mat4(1.0), Vec3(0.3, 0.1, 1.0)), farAt = glm::translate(Mat4(1.0), Vec3(-0.2, 0.0, -1.0));
    test::Scene both, nearOnly, farOnly;
    both.add(farBox, farAt);  // listed far first: the renderer sorts
    both.add(nearBox, nearAt);
    nearOnly.add(nearBox, nearAt);
    farOnly.add(farBox, farAt);
    const Camera camera = test::makeCamera(Vec3(0.5, 0.8, 4.0), Vec3(0.0));
    RendererOptions options;
    options.countFragments = true;
    GlRenderer renderer(context, options);
    const auto fragmentsOf = [&](const test::Scene& scene, DrawProbe probe, Image* image = nullptr) {
        RendererOptions o = options;
        o.probe = probe;
        renderer.setOptions(o);
        const Image frame = test::renderFrame(renderer, camera, scene);
        if (image) *image = frame;
        return renderer.statistics().fragments;
    };
    Image plain, again, depthOnly;
    const std::uint64_t passed = fragmentsOf(both, DrawProbe::None, &plain);
    const std::uint64_t nearAlone = fragmentsOf(nearOnly, DrawProbe::None), farAlone = fragmentsOf(farOnly, DrawProbe::None);
    const std::uint64_t everyFragment = fragmentsOf(both, DrawProbe::NoDepthRejection);
    EXPECT_GT(nearAlone, 1000u);
    EXPECT_EQ(passed, test::coveredPixels(plain));
    EXPECT_EQ(everyFragment, nearAlone + farAlone);
    EXPECT_LT(passed, everyFragment);  // the near box hides part of the far one
    const std::uint64_t triangles = renderer.statistics().triangles;
    EXPECT_LE(fragmentsOf(both, DrawProbe::SetUpOnly), 64u);
    EXPECT_EQ(renderer.statistics().triangles, triangles);  // every triangle still sent
    EXPECT_EQ(fragmentsOf(both, DrawProbe::DepthOnly, &depthOnly), passed);
    EXPECT_EQ(test::coveredPixels(depthOnly), 0u);
    EXPECT_EQ(fragmentsOf(both, DrawProbe::OneColour), passed);  // the same fragments pass
    // A checker-textured quad, shaded per pixel when drawn: one colour per triangle under the probe.
    test::Scene checker;
    checker.add(test::drawable(makeQuad(2.0f, 2.0f, makeCheckerImage(64, 8, {255, 0, 0, 255}, {255, 255, 255, 255}))), Mat4(1.0));
    Image textured, oneColour;
    const std::uint64_t quadFragments = fragmentsOf(checker, DrawProbe::None, &textured);
    EXPECT_EQ(fragmentsOf(checker, DrawProbe::OneColour, &oneColour), quadFragments);
    EXPECT_EQ(test::coveredPixels(oneColour), test::coveredPixels(textured));
    EXPECT_GT(testkit::compareImages(textured, oneColour, 8).fractionOverThreshold, 0.1);
    EXPECT_EQ(fragmentsOf(both, DrawProbe::None, &again), passed);
    EXPECT_EQ(testkit::compareImages(plain, again).maxChannelDifference, 0);
    // Not counting: the statistic stays zero.
    renderer.setOptions(RendererOptions{});
    test::renderFrame(renderer, camera, both);
    EXPECT_EQ(renderer.statistics().fragments, 0u);
}

TEST_F(RendererTest, MeshesAndTexturesAreUploadedOnceAndReleasedWhenGone) {
    GlRenderer renderer(context);
    const Camera camera = test::makeCamera(Vec3(0, 0, 3), Vec3(0.0));
    auto texture = makeCheckerImage(16, 4, {255, 0, 0, 255}, {255, 255, 255, 255});
    {
        test::Scene scene;
        auto quad = test::drawable(makeQuad(1.0f, 1.0f, texture));
        auto quad2 = test::drawable(makeQuad(0.5f, 0.5f, texture));  // same texture, another mesh
        scene.add(quad, Mat4(1.0));
        scene.add(quad, glm::translate(Mat4(1.0), Vec3(1, 0, 0)));
        scene.add(quad2, glm::translate(Mat4(1.0), Vec3(-1, 0, 0)));
        test::renderFrame(renderer, camera, scene);
        EXPECT_EQ(renderer.statistics().meshUploads, 2u);
        EXPECT_EQ(renderer.statistics().textureUploads, 1u);
        test::renderFrame(renderer, camera, scene);
        EXPECT_EQ(renderer.statistics().meshUploads, 0u);
        EXPECT_EQ(renderer.statistics().textureUploads, 0u);
        EXPECT_EQ(renderer.cachedMeshCount(), 2u);
        EXPECT_EQ(renderer.cachedTextureCount(), 1u);
    }
    texture.reset();
    renderer.releaseUnusedResources();  // the scene, its meshes and the texture are gone
    EXPECT_EQ(renderer.cachedMeshCount(), 0u);
    EXPECT_EQ(renderer.cachedTextureCount(), 0u);
}

TEST_F(RendererTest, OtherDrawablesAreSkippedAndCounted) {
    GlRenderer renderer(context);
    test::Scene scene;
    scene.add(std::make_shared<Drawable>("bare", BoundingSphere(Vec3(0.0), 1.0), 12), Mat4(1.0));
    scene.add(test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.5f))), Mat4(1.0));
    test::renderFrame(renderer, test::makeCamera(Vec3(0, 0, 3), Vec3(0.0)), scene);
    EXPECT_EQ(renderer.statistics().skippedItems, 1u);
    EXPECT_EQ(renderer.statistics().instances, 1u);
    EXPECT_EQ(renderer.statistics().drawCalls, 1u);
}

TEST_F(RendererTest, SkinnedMeshWithoutPaletteDrawsItsBindPose) {
    GlRenderer renderer(context);
    SkinnedTubeOptions options;
    test::Scene bindPose, identity;
    const auto tube = test::drawable(makeSkinnedTube(options));
    const std::vector<glm::mat4> identityPalette(2, glm::mat4(1.0f));
    bindPose.add(tube, glm::translate(Mat4(1.0), Vec3(0, -1, 0)));
    identity.add(tube, glm::translate(Mat4(1.0), Vec3(0, -1, 0)), glm::vec4(1.0f), &identityPalette);
    const Camera camera = test::makeCamera(Vec3(0, 0, 4), Vec3(0.0));
    const Image a = test::renderFrame(renderer, camera, bindPose);
    EXPECT_EQ(renderer.statistics().gpuSkinnedVertices, 0u);
    const Image b = test::renderFrame(renderer, camera, identity);
    EXPECT_GT(renderer.statistics().gpuSkinnedVertices, 0u);
    EXPECT_LE(testkit::compareImages(a, b, 2).pixelsOverThreshold, 0u);
}

TEST_F(RendererTest, ClearColourViewportSizeAndCapture) {
    RendererOptions options;
    options.clearColor = glm::vec4(1.0f, 0.0f, 0.5f, 1.0f);
    options.width = 64;
    options.height = 48;
    options.captureFrames = true;
    GlRenderer renderer(context, options);
    EXPECT_EQ(renderer.width(), 64);
    EXPECT_EQ(renderer.height(), 48);
    test::Scene empty;
    renderer.beginFrame(test::makeCamera(Vec3(0, 0, 3), Vec3(0.0)));
    renderer.draw(empty.list());
    renderer.endFrame();
    const Image& frame = renderer.lastFrame();
    ASSERT_TRUE(frame.valid());
    EXPECT_EQ(frame.width, 64);
    EXPECT_EQ(frame.height, 48);
    for (std::size_t i = 0; i < frame.rgba.size(); i += 4) {
        ASSERT_EQ(frame.rgba[i], 255);
        ASSERT_EQ(frame.rgba[i + 1], 0);
        ASSERT_NEAR(frame.rgba[i + 2], 128, 1);
    }
    renderer.setViewportSize(32, 16);
    EXPECT_EQ(renderer.readFrame().width, 32);
    EXPECT_EQ(context->width(), 32);
}

TEST_F(RendererTest, DrawsAFrameOfTraditionalProcessing) {
    auto root = std::make_shared<Transform>();
    for (int i = 0; i < 3; ++i) {
        auto t = std::make_shared<Transform>();
        TransformDofs dofs;
        dofs.translation = Vec3(-1.2 + 1.2 * i, 0, 0);
        t->setDofs(dofs);
        t->addChild(std::make_shared<Geometry>(test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.4f)))));
        root->addChild(t);
    }
    GlRenderer renderer(context);
    TraditionalProcessor processor;
    processor.processFrame(*root, test::makeCamera(Vec3(0, 1, 4), Vec3(0.0)), 0.0, &renderer);
    EXPECT_EQ(renderer.statistics().instances, 3u);
    EXPECT_EQ(renderer.statistics().triangles, 36u);
    EXPECT_GT(test::coveredPixels(renderer.readFrame()), 1500u);
}

TEST_F(RendererTest, TwoContextsInOneProcess) {
    auto other = std::make_shared<OsMesaContext>(kWidth, kHeight);
    GlRenderer first(context), second(other);
    test::Scene scene;
    scene.add(test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.5f))), glm::rotate(Mat4(1.0), 0.5, Vec3(0, 1, 0)));
    const Camera camera = test::makeCamera(Vec3(0, 1, 3), Vec3(0.0));
    const Image a = test::renderFrame(first, camera, scene);
    const Image b = test::renderFrame(second, camera, scene);
    const Image c = test::renderFrame(first, camera, scene);
    EXPECT_EQ(testkit::compareImages(a, b).maxChannelDifference, 0);
    EXPECT_EQ(testkit::compareImages(a, c).maxChannelDifference, 0);
    EXPECT_GT(test::coveredPixels(a), 1000u);
}

TEST_F(RendererTest, ShortPaletteIsRejectedBeforeDrawing) {
    GlRenderer renderer(context);
    SkinnedTubeOptions options;
    options.joints = 4;
    auto mesh = makeSkinnedTube(options);
    mesh->name = "four-joint tube";
    const std::vector<glm::mat4> palette(3, glm::mat4(1.0f));
    test::Scene scene;
    scene.add(test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.5f))), Mat4(1.0));
    scene.add(test::drawable(mesh), Mat4(1.0), glm::vec4(1.0f), &palette);
    renderer.beginFrame(test::makeCamera(Vec3(0, 0, 3), Vec3(0.0)));
    const std::string what = errorOf([&] { renderer.draw(scene.list()); });
    EXPECT_NE(what.find("item 1"), std::string::npos) << what;
    EXPECT_NE(what.find("four-joint tube"), std::string::npos) << what;
    EXPECT_NE(what.find("palette has 3 matrices"), std::string::npos) << what;
    EXPECT_NE(what.find("need 4"), std::string::npos) << what;
    EXPECT_EQ(renderer.statistics().drawCalls, 0u);  // nothing of the list was drawn
    renderer.endFrame();
    EXPECT_EQ(test::coveredPixels(renderer.readFrame()), 0u);
}

TEST_F(RendererTest, BadSizesAreClearErrors) {
    EXPECT_NE(errorOf([] { OsMesaContext c(0, 120); }).find("must be positive"), std::string::npos);
    EXPECT_NE(errorOf([] { OsMesaContext c(160, -1); }).find("must be positive"), std::string::npos);
    EXPECT_NE(errorOf([] { OsMesaContext c(1000000, 10); }).find("exceeds"), std::string::npos);
    GlRenderer renderer(context);
    EXPECT_NE(errorOf([&] { renderer.setViewportSize(0, 120); }).find("width 0 must be positive"), std::string::npos);
    EXPECT_NE(errorOf([&] { renderer.setViewportSize(160, 0); }).find("height 0 must be positive"), std::string::npos);
    RendererOptions negative;
    negative.width = -5;
    EXPECT_THROW(GlRenderer(context, negative), std::invalid_argument);
    EXPECT_THROW(renderer.setOptions(negative), std::invalid_argument);
    EXPECT_THROW(GlRenderer(nullptr), std::invalid_argument);
    EXPECT_THROW(context->resize(100000, 100000), std::invalid_argument);
    EXPECT_EQ(context->width(), kWidth);  // the failed resize kept the old framebuffer
    EXPECT_EQ(renderer.readFrame().height, kHeight);
}

TEST_F(RendererTest, MisuseIsAClearError) {
    GlRenderer renderer(context);
    test::Scene scene;
    EXPECT_NE(errorOf([&] { renderer.draw(scene.list()); }).find("outside beginFrame"), std::string::npos);
    EXPECT_THROW(renderer.endFrame(), std::logic_error);
    DrawList list;
    auto box = test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(1.0f)));
    DrawItem item;
    item.drawable = box.get();
    item.world.translation.y = std::nan("");  // but nowhere
    list.add(item, 12);
    renderer.beginFrame(test::makeCamera(Vec3(0, 0, 3), Vec3(0.0)));
    EXPECT_NE(errorOf([&] { renderer.draw(list); }).find("item 0 (drawable 'box') has a non-finite transform"),
              std::string::npos);
    renderer.endFrame();
}

TEST_F(RendererTest, ShaderErrorsCarryTheLog) {
    const std::string vertex = "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n";
    const std::string fragment = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    EXPECT_NO_THROW(ShaderProgram(*context, "fine", vertex, fragment));
    const std::string compile =
        errorOf([&] { ShaderProgram(*context, "broken", "#version 330 core\nvoid main() { undeclared = 1; }\n", fragment); });
    EXPECT_NE(compile.find("broken: the vertex shader failed to compile"), std::string::npos) << compile;
    EXPECT_NE(compile.find("undeclared"), std::string::npos) << compile;  // the driver's log
    const std::string fragmentError = errorOf([&] { ShaderProgram(*context, "broken", vertex, "#version 330 core\nvoid main() { x; }\n"); });
    EXPECT_NE(fragmentError.find("fragment shader failed to compile"), std::string::npos) << fragmentError;
    const std::string link = errorOf([&] {
        ShaderProgram(*context, "unlinkable", "#version 330 core\nvoid f();\nvoid main() { f(); gl_Position = vec4(0.0); }\n",
                      fragment);
    });
    EXPECT_NE(link.find("unlinkable: the program failed to link"), std::string::npos) << link;
}

}  // namespace
}  // namespace throng
