// Context creation: headless by default, a window only with a display (the window test skips
// otherwise), and clear errors when a context cannot be made.

#include <gtest/gtest.h>

#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "RenderTestSupport.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/EglContext.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/GlfwWindowContext.h"
#include "throng/render/OsMesaContext.h"
#include "throng/render/ProceduralMeshes.h"

namespace throng {
namespace {

TEST(ContextTest, HeadlessContextIsCoreProfileOnOsMesa) {
    OsMesaContext context(test::kWidth, test::kHeight);
    EXPECT_TRUE(context.headless());
    EXPECT_NE(context.framebuffer(), 0u);
    EXPECT_NE(context.description().find("OSMesa"), std::string::npos) << context.description();
    EXPECT_NE(context.description().find("Core Profile"), std::string::npos) << context.description();
}

TEST(ContextTest, EglSurfacelessIsCoreProfileAndResizes) {
    EglContext context(test::kWidth, test::kHeight, EglContext::Platform::Surfaceless);
    EXPECT_TRUE(context.headless());
    EXPECT_NE(context.framebuffer(), 0u);
    EXPECT_EQ(context.kind(), "EGL surfaceless (headless)");
    EXPECT_NE(context.version().find("Core Profile"), std::string::npos) << context.version();
    EXPECT_FALSE(context.renderer().empty());
    context.resize(64, 32);
    EXPECT_EQ(context.width(), 64);
    EXPECT_EQ(context.height(), 32);
    EXPECT_THROW(context.resize(0, 32), std::invalid_argument);
    EXPECT_EQ(context.width(), 64) << "a refused size keeps the framebuffer";
}

TEST(ContextTest, TheKindAskedForIsTheKindMade) {
    ContextOptions options;
    options.width = 32;
    options.height = 24;
    options.api = GlApi::OsMesa;
    EXPECT_EQ(createContext(options)->kind(), "OSMesa (headless)");
    options.api = GlApi::Egl;
    const auto egl = createContext(options);
    EXPECT_EQ(egl->kind(), EglContext::hardwareDevicePresent() ? "EGL device (headless)" : "EGL surfaceless (headless)");
    for (GlApi api : {GlApi::Auto, GlApi::Window, GlApi::Egl, GlApi::OsMesa}) EXPECT_EQ(glApiFromName(glApiName(api)), api);
    EXPECT_THROW(glApiFromName("vulkan"), std::invalid_argument);
    if (!displayAvailable()) {
        options.api = GlApi::Window;
        try {
            createContext(options);
            ADD_FAILURE() << "a window was made without a display";
        } catch (const ContextUnavailable& e) {
            EXPECT_NE(std::string(e.what()).find("try --gl egl"), std::string::npos) << e.what();
        }
    }
}

TEST(ContextTest, AnEglDeviceWithoutAGpuIsAClearError) {
    if (EglContext::hardwareDevicePresent()) GTEST_SKIP() << "a GPU is present: this checks the error without one";
    try {
        EglContext context(32, 24, EglContext::Platform::Device);
        ADD_FAILURE() << "an EGL device context without a hardware device";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("no EGL device with OpenGL 3.3 core"), std::string::npos) << e.what();
    }
}

TEST(ContextTest, FactoryGivesHeadlessUnlessAWindowIsAskedForAndPossible) {
    ContextOptions options;
    options.width = 96;
    options.height = 64;
    auto headless = createContext(options);
    EXPECT_TRUE(headless->headless());
    EXPECT_EQ(headless->width(), 96);
    options.window = true;
    std::string reason;
    auto chosen = createContext(options, &reason);
    if (!displayAvailable()) {
        EXPECT_TRUE(chosen->headless());
        EXPECT_NE(reason.find("no display"), std::string::npos) << reason;
    } else {
        EXPECT_TRUE(!chosen->headless() || !reason.empty()) << "a window was asked for, with a display";
    }
    options.width = 0;
    EXPECT_THROW(createContext(options), std::invalid_argument);
}

TEST(ContextTest, WindowWithoutDisplayIsAClearError) {
    if (displayAvailable()) GTEST_SKIP() << "a display exists: this checks the error without one";
    try {
        GlfwWindowContext window(64, 48, "no display");
        ADD_FAILURE() << "a window opened without a display";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("GlfwWindowContext"), std::string::npos) << e.what();
    }
}

// With a display (e.g. under xvfb-run), a hidden window renders what the headless context renders.
TEST(ContextTest, WindowRendersLikeHeadless) {
    if (!displayAvailable()) GTEST_SKIP() << "no display (DISPLAY/WAYLAND_DISPLAY unset): window test skipped";
    std::shared_ptr<GlfwWindowContext> window;
    try {
        window = std::make_shared<GlfwWindowContext>(test::kWidth, test::kHeight, "Throng test", false);
    } catch (const std::runtime_error& e) {
        GTEST_SKIP() << "a display is set but no window could be opened: " << e.what();
    }
    EXPECT_FALSE(window->headless());
    test::Scene scene;
    scene.add(test::drawable(makeBox("box", glm::vec3(0.0f), glm::vec3(0.5f), glm::vec4(0.2f, 0.6f, 0.9f, 1.0f))),
              glm::rotate(Mat4(1.0), 0.7, Vec3(0.3, 1, 0)));
    const Camera camera = test::makeCamera(Vec3(0, 0.5, 3), Vec3(0.0));
    GlRenderer onScreen(window);
    const Image a = test::renderFrame(onScreen, camera, scene);
    GlRenderer offScreen(std::make_shared<OsMesaContext>(test::kWidth, test::kHeight));
    const Image b = test::renderFrame(offScreen, camera, scene);
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    // Another driver may sit behind the window: compare loosely.
    const testkit::ImageDifference d = testkit::compareImages(a, b, 16);
    EXPECT_LE(d.fractionOverThreshold, 0.02) << window->description();
    EXPECT_GT(test::coveredPixels(a), 1000u);
    RecordProperty("window", window->description());
    RecordProperty("max_channel_difference", d.maxChannelDifference);
}

}  // namespace
}  // namespace throng
