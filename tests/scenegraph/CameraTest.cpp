// Camera: argument checks and the eye position.

#include <gtest/gtest.h>

#include <limits>
#include <numbers>

#include "throng/scenegraph/Camera.h"

using namespace throng;

TEST(Camera, RejectsBadPerspectivesNamingTheArgument) {
    Camera c;
    auto expectMessage = [&](auto call, const char* text) {
        try {
            call();
            FAIL() << "accepted: " << text;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
        }
    };
    expectMessage([&] { c.setPerspective(0.0, 1, 1, 10); }, "fovYRadians");
    expectMessage([&] { c.setPerspective(std::numbers::pi, 1, 1, 10); }, "fovYRadians");
    expectMessage([&] { c.setPerspective(1, -1, 1, 10); }, "aspect");
    expectMessage([&] { c.setPerspective(1, 1, 0, 10); }, "nearDistance");
    expectMessage([&] { c.setPerspective(1, 1, 10, 10); }, "farDistance");
    expectMessage([&] { c.setPerspective(1, 1, 1, std::numeric_limits<double>::infinity()); }, "farDistance");
    expectMessage([&] { c.setLookAt(Vec3(1), Vec3(1)); }, "coincide");
    expectMessage([&] { c.setLookAt(Vec3(0), Vec3(0, 1, 0), Vec3(0, 1, 0)); }, "'up'");
    expectMessage([&] { c.setLookAt(Vec3(0, std::numeric_limits<double>::quiet_NaN(), 0), Vec3(1)); }, "'eye'");
}

TEST(Camera, EyeFromLookAtAndFromViewMatrixAgree) {
    Camera a;
    a.setLookAt(Vec3(3, 4, 5), Vec3(0, 0, 0));
    EXPECT_EQ(a.eye(), Vec3(3, 4, 5));
    Camera b;
    b.setViewMatrix(a.view());
    EXPECT_NEAR(glm::length(b.eye() - Vec3(3, 4, 5)), 0.0, 1e-12);
    EXPECT_THROW(b.setViewMatrix(Mat4(0.0)), std::invalid_argument);
}
