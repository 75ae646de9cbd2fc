// Frustum: plane extraction, sphere classification checked against brute force on 10^5 random
// spheres and frusta, and plane masks.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/testkit/RandomScenes.h"

using namespace throng;

namespace {

// Independent inside test: the clip-space conditions -w <= x, y, z <= w of the matrix itself.
bool insideClipVolume(const Mat4& vp, const Vec3& p) {
    const Vec4 c = vp * Vec4(p, 1.0);
    return c.w > 0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && std::abs(c.z) <= c.w;
}

// Nearest point of the frustum to `p`, by Dykstra's alternating projections onto its half-spaces:
// independent of the classification code, and exact in the limit.
Vec3 nearestPointInFrustum(const Frustum& f, const Vec3& p, int iterations = 400) {
    Vec3 x = p;
    std::array<Vec3, 6> corrections{};
    for (int it = 0; it < iterations; ++it) {
        for (int i = 0; i < 6; ++i) {
            const Vec4& pl = f.plane(i);
            const Vec3 n(pl);
            const Vec3 y = x + corrections[i];
            const double d = glm::dot(n, y) + pl.w;
            const Vec3 proj = d < 0 ? y - d * n : y;
            corrections[i] = y - proj;
            x = proj;
        }
    }
    return x;
}

}  // namespace

TEST(Frustum, PlanesOfASimplePerspectiveAreNormalizedAndPointInward) {
    Camera cam;
    cam.setPerspective(std::numbers::pi / 2, 1.0, 1.0, 100.0);
    cam.setLookAt(Vec3(0.0), Vec3(0, 0, -1), Vec3(0, 1, 0));
    const Frustum f = cam.frustum();
    EXPECT_EQ(f.activePlanes(), Frustum::kAllPlanes);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(glm::length(Vec3(f.plane(i))), 1.0, 1e-12);
    EXPECT_NEAR(f.plane(Frustum::kNear).w, -1.0, 1e-9);   // z = -1 plane, normal (0,0,-1)
    EXPECT_NEAR(f.plane(Frustum::kFar).w, 100.0, 1e-9);
    EXPECT_TRUE(f.contains(Vec3(0, 0, -50)));
    EXPECT_FALSE(f.contains(Vec3(0, 0, 50)));
    EXPECT_FALSE(f.contains(Vec3(60, 0, -50)));  // 90 degree fov: |x| <= |z|
    EXPECT_TRUE(f.contains(Vec3(49, 0, -50)));
}

TEST(Frustum, ClassifiesKnownSpheres) {
    Camera cam;
    cam.setPerspective(std::numbers::pi / 2, 1.0, 1.0, 100.0);
    cam.setLookAt(Vec3(0.0), Vec3(0, 0, -1), Vec3(0, 1, 0));
    const Frustum f = cam.frustum();
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, -50), 1)), Containment::Inside);
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, 50), 1)), Containment::Outside);
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, -100), 1)), Containment::Intersects);
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, 0), 0.5)), Containment::Outside);  // before the near plane
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, 0), 2.0)), Containment::Intersects);
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, -50), 1000)), Containment::Intersects);
    EXPECT_EQ(f.classify(BoundingSphere()), Containment::Outside) << "an empty sphere holds nothing";
}

TEST(Frustum, NeverRejectsASphereHoldingAVisiblePointOnRandomCases) {
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> u(-1, 1);
    int outside = 0, inside = 0, intersects = 0;
    constexpr int kCases = 100000;
    for (int i = 0; i < kCases; ++i) {
        const Camera cam = testkit::randomCamera(rng, 100.0);
        const Mat4 vp = cam.viewProjection();
        const Frustum f = Frustum::fromViewProjection(vp);
        const Vec3 c = cam.eye() + Vec3(u(rng), u(rng), u(rng)) * 150.0;
        const double r = std::exp(std::uniform_real_distribution<double>(std::log(1e-3), std::log(100.0))(rng));
        const BoundingSphere s(c, r);
        const Containment got = f.classify(s);
        // Sample the sphere: the centre, axis extremes and random points in its volume.
        std::vector<Vec3> samples{c};
        for (int a = 0; a < 3; ++a)
            for (double sign : {-1.0, 1.0}) {
                Vec3 d(0.0);
                d[a] = sign * r;
                samples.push_back(c + d);
            }
        for (int k = 0; k < 24; ++k) {
            Vec3 d(u(rng), u(rng), u(rng));
            if (glm::length(d) > 1.0) d /= glm::length(d);
            samples.push_back(c + d * r);
        }
        bool anyInside = false, allInside = true;
        for (const Vec3& p : samples) {
            const bool in = insideClipVolume(vp, p);
            anyInside = anyInside || in;
            allInside = allInside && in;
        }
        switch (got) {
            case Containment::Outside: {
                ++outside;
                ASSERT_FALSE(anyInside) << "case " << i << ": a visible point was rejected";
                const Vec3 q = nearestPointInFrustum(f, c);
                ASSERT_GT(glm::length(q - c), r * (1 - 1e-6)) << "case " << i << ": the frustum reaches into the sphere";
                break;
            }
            case Containment::Inside:
                ++inside;
                ASSERT_TRUE(allInside) << "case " << i << ": a sphere reported inside has a point outside";
                break;
            case Containment::Intersects:
                ++intersects;
                break;
        }
    }
    // The random cases must exercise every answer.
    EXPECT_GT(outside, kCases / 10);
    EXPECT_GT(inside, kCases / 100);
    EXPECT_GT(intersects, kCases / 100);
}

TEST(Frustum, PlaneMaskSkipsPlanesAParentIsInside) {
    Camera cam;
    cam.setPerspective(std::numbers::pi / 2, 1.0, 1.0, 100.0);
    cam.setLookAt(Vec3(0.0), Vec3(0, 0, -1), Vec3(0, 1, 0));
    const Frustum f = cam.frustum();
    // A parent crossing only the right plane: every other bit is cleared.
    const BoundingSphere parent(Vec3(45, 0, -50), 8);
    PlaneMask mask = f.activePlanes();
    OpTally ops;
    ASSERT_EQ(f.classify(parent, mask, &ops), Containment::Intersects);
    EXPECT_EQ(mask, PlaneMask(1u << Frustum::kRight));
    EXPECT_EQ(ops.mults, 6u * 3u) << "all six planes tested for the parent";
    // Its child is then tested against the right plane alone.
    OpTally childOps;
    PlaneMask childMask = mask;
    const BoundingSphere child(Vec3(40, 0, -50), 1);
    EXPECT_EQ(f.classify(child, childMask, &childOps), Containment::Inside);
    EXPECT_EQ(childMask, 0);
    EXPECT_EQ(childOps.mults, 3u) << "one plane tested for the child";
    // With an empty mask the answer is Inside without any plane test (only the sphere's emptiness
    // is checked).
    OpTally none;
    PlaneMask empty = 0;
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, 1000), 1), empty, &none), Containment::Inside);
    EXPECT_EQ(none.mults, 0u);
}

TEST(Frustum, RejectsNonFiniteAndEmptyVolumes) {
    Mat4 m(1.0);
    m[2][1] = std::numeric_limits<double>::quiet_NaN();
    try {
        Frustum::fromViewProjection(m);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("viewProjection"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("[column 2][row 1]"), std::string::npos) << e.what();
    }
    Mat4 zero(0.0);
    zero[3][3] = -1.0;  // w = -1 everywhere: no point satisfies -w <= x <= w
    EXPECT_THROW(Frustum::fromViewProjection(zero), std::invalid_argument);
}

TEST(Frustum, InfiniteFarPlaneIsInactive) {
    const Mat4 proj = glm::infinitePerspective(1.0, 1.5, 0.1);
    const Frustum f = Frustum::fromViewProjection(proj);
    EXPECT_EQ(f.activePlanes() & (1u << Frustum::kFar), 0u);
    EXPECT_EQ(f.classify(BoundingSphere(Vec3(0, 0, -1e12), 1.0)), Containment::Inside);
}
