// Numerical hard cases of DESIGN.md for the generic scenegraph: coordinates of 10^6-10^7 m,
// degenerate spheres, extreme frusta (narrow, wide, near 1e-4, far 1e7, infinite), the camera inside
// a sphere, and NaN/Inf rejected at the API.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "throng/testkit/Cameras.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/SphereArrayCuller.h"
#include "throng/scenegraph/TraditionalProcessor.h"
#include "throng/scenegraph/Transform.h"
#include "throng/testkit/RandomScenes.h"

using namespace throng;

namespace {

Camera cameraAt(const Vec3& eye, const Vec3& target, double fov = 1.0, double nearD = 0.1, double farD = 1000.0) {
    return testkit::lookingAt(eye, target, {fov, 1.5, nearD, farD});
}

}  // namespace

class FarFromOrigin : public ::testing::TestWithParam<double> {};

TEST_P(FarFromOrigin, MergeAndTransformKeepMillimetreAccuracy) {
    const double far = GetParam();
    const Vec3 base(far, -0.5 * far, far);
    BoundingSphere a(base, 0.3);
    a.expandBy(BoundingSphere(base + Vec3(1.0, 0, 0), 0.3));
    EXPECT_NEAR(a.radius(), 0.8, 1e-6);
    EXPECT_NEAR(a.center().x - base.x, 0.5, 1e-6);
    a.expandBy(BoundingSphere(base + Vec3(0.5, 0, 0), 0.0));  // coincident centre, zero radius
    EXPECT_NEAR(a.radius(), 0.8, 1e-6);

    Mat4 m = glm::mat4_cast(glm::angleAxis(0.4, Vec3(0, 1, 0)));
    m[3] = Vec4(base, 1.0);
    const BoundingSphere local(Vec3(0.2, 1.0, 0.0), 0.9);
    const BoundingSphere world = local.transformed(m);
    EXPECT_NEAR(world.radius(), 0.9, 1e-6);
    EXPECT_NEAR(glm::length(world.center() - Vec3(m * Vec4(local.center(), 1.0))), 0.0, 1e-6);
}

TEST_P(FarFromOrigin, CullsCorrectlyAtCentimetreMargins) {
    const double far = GetParam();
    const Vec3 eye(far, 2.0, far);
    const Camera cam = cameraAt(eye, eye + Vec3(0, 0, -1), std::numbers::pi / 2, 0.1, 1000.0);
    const Frustum f = cam.frustum();
    EXPECT_EQ(f.classify(BoundingSphere(eye + Vec3(0, 0, -50), 1)), Containment::Inside);
    EXPECT_EQ(f.classify(BoundingSphere(eye + Vec3(0, 0, 50), 1)), Containment::Outside);
    // 90 degree fov, aspect 1.5: the right plane at depth 50 is at x = 75. A 1 m sphere 1 cm beyond
    // it is outside; 1 cm inside it, it touches the volume.
    const double edge = 50.0 * 1.5;
    const double offset = 1.0 / std::cos(std::atan(1.5));  // centre distance to the plane for r = 1, along x
    EXPECT_EQ(f.classify(BoundingSphere(eye + Vec3(edge + offset + 0.01, 0, -50), 1.0)), Containment::Outside);
    EXPECT_EQ(f.classify(BoundingSphere(eye + Vec3(edge + offset - 0.01, 0, -50), 1.0)), Containment::Intersects);

    // A whole scene of nested transforms 10^6-10^7 m away culls as it does at the origin.
    std::mt19937_64 rngNear(42), rngFar(42);
    auto nearScene = testkit::buildRandomScene(rngNear, {.objects = 80});
    auto farScene = testkit::buildRandomScene(rngFar, {.objects = 80, .origin = Vec3(far, -0.5 * far, far)});
    const Camera nearCam = cameraAt(Vec3(0, 20, 300), Vec3(0.0));
    const Camera farCam = cameraAt(Vec3(far, -0.5 * far + 20, far + 300), Vec3(far, -0.5 * far, far));
    TraditionalProcessor pn, pf;
    pn.processFrame(*nearScene, nearCam, 0);
    pf.processFrame(*farScene, farCam, 0);
    ASSERT_EQ(pn.drawList().size(), pf.drawList().size());
    for (std::size_t i = 0; i < pn.drawList().size(); ++i)
        EXPECT_EQ(pn.drawList().items()[i].node->name(), pf.drawList().items()[i].node->name());
}

TEST_P(FarFromOrigin, FloatCullerIsCameraRelative) {
    const double far = GetParam();
    const Vec3 eye(far, 0, -far);
    const Camera cam = cameraAt(eye, eye + Vec3(1, 0, 0), 1.0, 0.1, 1000.0);
    const SphereArrayCuller culler(cam.frustum(), eye);
    std::vector<float> x = {50.0f, -50.0f, 1000.5f}, y = {0, 0, 0}, z = {0, 0, 0}, r = {0.5f, 0.5f, 0.4f};
    std::vector<Containment> out(3);
    culler.classify({x, y, z, r}, out);
    EXPECT_EQ(out[0], Containment::Inside);
    EXPECT_EQ(out[1], Containment::Outside);
    EXPECT_EQ(out[2], Containment::Outside) << "10 cm beyond the far plane";
}

INSTANTIATE_TEST_SUITE_P(Distances, FarFromOrigin, ::testing::Values(1e5, 1e6, 1e7));

TEST(DegenerateSpheres, ZeroRadiusCoincidentAndNested) {
    BoundingSphere s(Vec3(3, 3, 3), 0.0);
    for (int i = 0; i < 10; ++i) s.expandBy(BoundingSphere(Vec3(3, 3, 3), 0.0));
    EXPECT_EQ(s.radius(), 0.0);
    s.expandBy(BoundingSphere(Vec3(3, 3, 3), 2.0));
    EXPECT_EQ(s.radius(), 2.0);
    BoundingSphere nested(Vec3(0.0), 1.0);
    for (int i = 0; i < 100; ++i) nested.expandBy(BoundingSphere(Vec3(1e-3 * i, 0, 0), 0.5));
    EXPECT_EQ(nested, BoundingSphere(Vec3(0.0), 1.0));
    // Repeated merges of almost-coincident spheres stay finite and conservative.
    BoundingSphere grow(Vec3(0.0), 1.0);
    for (int i = 0; i < 10000; ++i) {
        const BoundingSphere other(Vec3(1e-12 * i, 0, 0), 1.0);
        grow.expandBy(other);
        ASSERT_TRUE(grow.contains(other));
    }
    EXPECT_LT(grow.radius(), 1.0 + 1e-6);
}

TEST(DegenerateSpheres, NonFiniteValuesAreRejectedAtTheApi) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    auto t = std::make_shared<Transform>();
    t->setName("hips");
    TransformDofs d;
    d.translation = Vec3(0, nan, 0);
    try {
        t->setDofs(d);
        FAIL();
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("'hips'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("dofs.translation"), std::string::npos) << msg;
    }
    d = {};
    d.rotation = Quat(0, 0, 0, 0);
    EXPECT_THROW(t->setDofs(d), std::invalid_argument);
    Mat4 projective(1.0);
    projective[0][3] = 0.5;
    EXPECT_THROW(t->setMatrix(projective), std::invalid_argument);
    EXPECT_FALSE(t->usesDofs()) << "rejected calls change nothing";
    TraditionalProcessor proc;
    auto root = std::make_shared<Group>();
    EXPECT_THROW(proc.processFrame(*root, Camera(), nan), std::invalid_argument);
    EXPECT_THROW(proc.setLodScale(0.0), std::invalid_argument);
}

TEST(ExtremeFrusta, VeryNarrowAndVeryWide) {
    const Camera narrow = cameraAt(Vec3(0.0), Vec3(0, 0, -1), 1e-4, 0.1, 1e4);
    const Frustum fn = narrow.frustum();
    // At 5 km a 1e-4 rad view is 0.5 m tall and 0.75 m wide.
    EXPECT_EQ(fn.classify(BoundingSphere(Vec3(0, 0, -5000), 0.2)), Containment::Inside);
    EXPECT_EQ(fn.classify(BoundingSphere(Vec3(0, 0, -5000), 0.3)), Containment::Intersects);
    EXPECT_EQ(fn.classify(BoundingSphere(Vec3(0, 0.6, -5000), 0.3)), Containment::Outside);
    EXPECT_EQ(fn.classify(BoundingSphere(Vec3(2, 0, -5000), 0.5)), Containment::Outside);

    const Camera wide = cameraAt(Vec3(0.0), Vec3(0, 0, -1), std::numbers::pi * 0.9999, 0.1, 1e4);
    const Frustum fw = wide.frustum();
    // 179.98 degrees: a point 89.9 degrees off the axis is well inside, one at 90.1 degrees outside.
    EXPECT_EQ(fw.classify(BoundingSphere(Vec3(5000, 0, -10), 0.5)), Containment::Inside);
    EXPECT_EQ(fw.classify(BoundingSphere(Vec3(5000, 0, 10), 0.5)), Containment::Outside);
    EXPECT_EQ(fw.classify(BoundingSphere(Vec3(0, 0, 5), 0.5)), Containment::Outside);     // behind
}

TEST(ExtremeFrusta, NearOneTenthMillimetreFarTenThousandKilometres) {
    const Camera cam = cameraAt(Vec3(0.0), Vec3(0, 0, -1), 1.0, 1e-4, 1e7);
    const Frustum f = cam.frustum();
    EXPECT_EQ(f.activePlanes(), Frustum::kAllPlanes);
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, -5e-4), 1e-4)), Containment::Inside);
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, -5e-5), 1e-5)), Containment::Outside) << "before the near plane";
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, -5e6), 1e3)), Containment::Inside);
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, -1.01e7), 1e3)), Containment::Outside) << "beyond the far plane";
    for (int i = 0; i < 6; ++i) EXPECT_TRUE(std::isfinite(f.plane(i).w));
}

TEST(ExtremeFrusta, CameraInsideASphere) {
    const Camera cam = cameraAt(Vec3(10, 0, 10), Vec3(10, 0, 0), 1.0, 0.1, 1000.0);
    const Frustum f = cam.frustum();
    // A sphere around the eye always holds the start of the view volume.
    for (double r : {0.2, 1.0, 10.0, 400.0})
        EXPECT_NE(f.classify(BoundingSphere(cam.eye(), r)), Containment::Outside) << r;
    // A sphere holding the whole frustum crosses its planes: Intersects, never Outside or Inside.
    EXPECT_EQ(f.classify(BoundingSphere(cam.eye(), 1e5)), Containment::Intersects);
    // Culling a scene whose every node holds the eye draws everything in view.
    auto root = std::make_shared<Group>();
    auto big = std::make_shared<Drawable>("room", BoundingSphere(Vec3(0.0), 50.0), 1000);
    auto t = std::make_shared<Transform>();
    TransformDofs d;
    d.translation = cam.eye();
    t->setDofs(d);
    t->addChild(std::make_shared<Geometry>(big));
    root->addChild(t);
    TraditionalProcessor proc;
    proc.processFrame(*root, cam, 0);
    EXPECT_EQ(proc.drawList().size(), 1u);
}
