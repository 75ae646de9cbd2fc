// FMULT tallies of the scenegraph's kernels checked against the operations they execute: each
// kernel runs on counting numbers (the same template production compiles for double and float)
// over inputs that take every branch, and its hand-written THRONG_TALLY must equal the count. The
// counting run must also give the production result bit for bit, so the code counted is the code
// that runs.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <random>

#include "KernelCheck.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/SphereArrayCuller.h"
#include "throng/scenegraph/Transform.h"
#include "throng/scenegraph/detail/BoundingSphereImpl.h"
#include "throng/scenegraph/detail/FrustumKernel.h"
#include "throng/scenegraph/detail/LodKernels.h"
#include "throng/scenegraph/detail/TransformKernels.h"

using namespace throng;
using namespace throng::counting;

namespace {

using CSphere = BasicBoundingSphere<CDouble>;
using CVec3 = glm::vec<3, CDouble>;
using CVec4 = glm::vec<4, CDouble>;
using CMat4 = glm::mat<4, 4, CDouble>;
using CQuat = glm::qua<CDouble>;

CVec3 counted(const Vec3& v) { return CVec3(v); }
CMat4 counted(const Mat4& m) { return CMat4(m); }

void expectSame(const CSphere& c, const BoundingSphere& s, const std::string& what) {
    EXPECT_EQ(c.radius().value(), s.radius()) << what;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(c.center()[i].value(), s.center()[i]) << what;
}

void expectSame(const CMat4& c, const Mat4& m, const std::string& what) {
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) EXPECT_EQ(c[col][row].value(), m[col][row]) << what;
}

struct Random {
    std::mt19937_64 rng{20240611};
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
    Vec3 point(double extent) { return Vec3(uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)); }
    Quat rotation() {
        return glm::normalize(Quat(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
    }
    // A rotation, non-uniform scale and translation; with `shear`, a general affine matrix.
    Mat4 affine(bool shear) {
        TransformDofs d;
        d.translation = point(50.0);
        d.rotation = rotation();
        d.scale = Vec3(uniform(0.2, 3.0), uniform(0.2, 3.0), uniform(0.2, 3.0));
        Mat4 m = matrixFromDofs(d);
        if (shear) m[1][0] += uniform(-0.5, 0.5), m[2][1] += uniform(-0.5, 0.5);
        return m;
    }
};

// Runs expandBy(point) on counting numbers and on double; checks tally and result.
void checkExpandByPoint(const BoundingSphere& s, const Vec3& p, const std::string& what) {
    CSphere c(s);
    expectTallyMatchesExecuted(what, [&](OpTally* hand) { c.expandBy(counted(p), hand); });
    BoundingSphere d = s;
    d.expandBy(p);
    expectSame(c, d, what);
}

void checkExpandBySphere(const BoundingSphere& s, const BoundingSphere& other, const std::string& what) {
    CSphere c(s);
    const CSphere o(other);
    expectTallyMatchesExecuted(what, [&](OpTally* hand) { c.expandBy(o, hand); });
    BoundingSphere d = s;
    d.expandBy(other);
    expectSame(c, d, what);
}

}  // namespace

TEST(CountedKernels, SphereGrowsToAPoint) {
    THRONG_SKIP_WITHOUT_COUNTING();
    const BoundingSphere unit(Vec3(1, 2, 3), 1.0);
    checkExpandByPoint(BoundingSphere(), Vec3(4, 5, 6), "empty sphere takes the point");
    checkExpandByPoint(unit, Vec3(1.5, 2, 3), "point inside");
    checkExpandByPoint(unit, Vec3(2, 2, 3), "point on the surface");
    checkExpandByPoint(unit, Vec3(10, -2, 3), "point outside");
    checkExpandByPoint(BoundingSphere(Vec3(0.0), 0.0), Vec3(0, 0, 1), "zero radius");
    Random r;
    for (int i = 0; i < 200; ++i)
        checkExpandByPoint(BoundingSphere(r.point(10.0), r.uniform(0.0, 5.0)), r.point(12.0), "random " + std::to_string(i));
}

TEST(CountedKernels, SphereMergeEveryCase) {
    THRONG_SKIP_WITHOUT_COUNTING();
    const BoundingSphere a(Vec3(0.0), 2.0);
    checkExpandBySphere(a, BoundingSphere(), "other empty");
    checkExpandBySphere(BoundingSphere(), a, "this empty");
    checkExpandBySphere(BoundingSphere(), BoundingSphere(), "both empty");
    checkExpandBySphere(a, BoundingSphere(Vec3(0.5, 0, 0), 1.0), "other inside");
    checkExpandBySphere(BoundingSphere(Vec3(0.5, 0, 0), 1.0), a, "this inside the other");
    checkExpandBySphere(a, BoundingSphere(Vec3(0.0), 2.0), "identical");
    checkExpandBySphere(a, BoundingSphere(Vec3(0.0), 3.0), "coincident centres, other larger");
    checkExpandBySphere(BoundingSphere(Vec3(0.0), 0.0), BoundingSphere(Vec3(0.0), 0.0), "coincident points");
    checkExpandBySphere(BoundingSphere(Vec3(0.0), 0.0), BoundingSphere(Vec3(1, 0, 0), 0.0), "two points");
    checkExpandBySphere(a, BoundingSphere(Vec3(5, 0, 0), 1.0), "disjoint");
    checkExpandBySphere(a, BoundingSphere(Vec3(2, 1, 0), 1.5), "overlapping");
    Random r;
    for (int i = 0; i < 300; ++i)
        checkExpandBySphere(BoundingSphere(r.point(5.0), r.uniform(0.0, 4.0)), BoundingSphere(r.point(5.0), r.uniform(0.0, 4.0)),
                            "random " + std::to_string(i));
}

TEST(CountedKernels, SphereTransform) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Random r;
    auto check = [](const BoundingSphere& s, const Mat4& m, const std::string& what) {
        const CSphere c(s);
        CSphere out;
        expectTallyMatchesExecuted(what, [&](OpTally* hand) { out = c.transformed(counted(m), hand); });
        expectSame(out, s.transformed(m), what);
    };
    check(BoundingSphere(), Mat4(1.0), "empty sphere");
    check(BoundingSphere(Vec3(1, 2, 3), 0.5), Mat4(1.0), "identity");
    check(BoundingSphere(Vec3(1, 2, 3), 0.0), r.affine(false), "zero radius");
    for (int i = 0; i < 100; ++i)
        check(BoundingSphere(r.point(3.0), r.uniform(0.0, 2.0)), r.affine(i % 2 == 1), "random " + std::to_string(i));
    // maxScaleFactor on its own.
    const Mat4 m = r.affine(true);
    CDouble f;
    expectTallyMatchesExecuted("maxScaleFactor", [&](OpTally* hand) { f = detail::maxScaleFactor(counted(m), hand); });
    EXPECT_EQ(f.value(), maxScaleFactor(m));
}

TEST(CountedKernels, FrustumClassifyWithPlaneMasks) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Camera camera;
    camera.setPerspective(std::numbers::pi / 3, 1.5, 0.5, 200.0);
    camera.setLookAt(Vec3(3, 2, 10), Vec3(0, 0, -20), Vec3(0, 1, 0));
    const Frustum finite = camera.frustum();
    // An infinite far plane: five active planes.
    const Frustum infinite = Frustum::fromViewProjection(glm::infinitePerspective(1.0, 1.5, 0.5) *
                                                         glm::lookAt(Vec3(0.0), Vec3(0, 0, -1), Vec3(0, 1, 0)));
    ASSERT_EQ(infinite.activePlanes(), Frustum::kAllPlanes & ~(1u << Frustum::kFar));
    std::array<int, 3> seen{};
    std::size_t masked = 0;
    for (const Frustum* f : {&finite, &infinite}) {
        std::array<CVec4, Frustum::kPlaneCount> planes;
        for (int i = 0; i < Frustum::kPlaneCount; ++i) planes[std::size_t(i)] = CVec4(f->plane(i));
        auto check = [&](const BoundingSphere& s, PlaneMask mask, const std::string& what) {
            PlaneMask countedMask = mask, mask2 = mask;
            Containment c{};
            expectTallyMatchesExecuted(what, [&](OpTally* hand) { c = detail::classifySphere(planes, CSphere(s), countedMask, hand); });
            EXPECT_EQ(c, f->classify(s, mask2)) << what;
            EXPECT_EQ(countedMask, mask2) << what;
            ++seen[std::size_t(c)];
            return std::make_pair(c, countedMask);
        };
        check(BoundingSphere(), f->activePlanes(), "empty sphere");
        check(BoundingSphere(Vec3(0, 0, -30), 1.0), 0, "no plane left to test");
        Random r;
        for (int i = 0; i < 300; ++i) {
            // A parent sphere, then a child inside it tested only against the planes it crosses.
            const BoundingSphere parent(r.point(60.0) + Vec3(0, 0, -40), r.uniform(0.0, 30.0));
            const auto [c, mask] = check(parent, f->activePlanes(), "parent " + std::to_string(i));
            if (c != Containment::Intersects) continue;
            masked += mask != f->activePlanes();
            const BoundingSphere child(parent.center() + r.point(parent.radius() * 0.5), parent.radius() * 0.4);
            check(child, mask, "child " + std::to_string(i));
        }
    }
    for (int k = 0; k < 3; ++k) EXPECT_GT(seen[std::size_t(k)], 10) << "outside, crossing and inside spheres";
    EXPECT_GT(masked, 10u) << "children tested with masks that skip planes";
}

TEST(CountedKernels, SphereArrayCullerPerSphere) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Camera camera;
    camera.setPerspective(1.0, 16.0 / 9.0, 0.1, 500.0);
    camera.setLookAt(Vec3(0, 2, 0), Vec3(0, 0, -100), Vec3(0, 1, 0));
    const SphereArrayCuller culler(camera.frustum(), camera.eye());
    detail::CullPlanes<CFloat> planes;
    const detail::CullPlanes<float>& p = culler.planes();
    for (int i = 0; i < Frustum::kPlaneCount; ++i) {
        const auto k = std::size_t(i);
        planes.nx[k] = p.nx[k], planes.ny[k] = p.ny[k], planes.nz[k] = p.nz[k], planes.d[k] = p.d[k],
        planes.margin[k] = p.margin[k];
    }
    Random r;
    std::vector<float> x, y, z, radius;
    for (int i = 0; i < 500; ++i) {
        const Vec3 c = r.point(300.0) - camera.eye();
        x.push_back(float(c.x)), y.push_back(float(c.y)), z.push_back(float(c.z)), radius.push_back(float(r.uniform(0.0, 30.0)));
    }
    std::vector<Containment> out(x.size());
    OpTally batch;
    culler.classify({x, y, z, radius}, out, &batch);
    OpTally perSphere = SphereArrayCuller::kOpsPerSphere;
    OpTally executed;
    std::array<int, 3> seen{};
    for (std::size_t i = 0; i < x.size(); ++i) {
        std::uint8_t c = 0;
        const OpTally one = executedBy([&] { c = detail::sphereContainment(CFloat(x[i]), CFloat(y[i]), CFloat(z[i]), CFloat(radius[i]), planes); });
        EXPECT_EQ(one, perSphere) << "sphere " << i << ": executed " << describe(one) << ", kOpsPerSphere " << describe(perSphere);
        EXPECT_EQ(c, static_cast<std::uint8_t>(out[i])) << "sphere " << i;
        ++seen[c];
        executed += one;
    }
    EXPECT_EQ(batch, executed) << "classify() tallies kOpsPerSphere per sphere";
    EXPECT_GT(seen[0], 0);
    EXPECT_GT(seen[1], 0);
    EXPECT_GT(seen[2], 0);
}

TEST(CountedKernels, MatrixFromDofsAndAffineProduct) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Random r;
    for (int i = 0; i < 50; ++i) {
        TransformDofs d;
        d.translation = r.point(10.0);
        d.rotation = r.rotation();
        d.scale = Vec3(r.uniform(0.5, 2.0), r.uniform(0.5, 2.0), r.uniform(0.5, 2.0));
        CMat4 m;
        expectTallyMatchesExecuted("matrixFromDofs", [&](OpTally* hand) {
            m = detail::matrixFromDofs(counted(d.translation), CQuat(d.rotation), counted(d.scale), hand);
        });
        expectSame(m, matrixFromDofs(d), "matrixFromDofs");
        const Mat4 a = r.affine(i % 2 == 0), b = r.affine(i % 3 == 0);
        CMat4 ab;
        expectTallyMatchesExecuted("composeAffine", [&](OpTally* hand) { ab = detail::composeAffine(counted(a), counted(b), hand); });
        expectSame(ab, composeAffine(a, b), "composeAffine");
    }
}

TEST(CountedKernels, GenericLodNodeDistanceAndChoice) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Random r;
    LOD lod;
    for (double d : {10.0, 40.0, 120.0}) lod.addChild(std::make_shared<Group>(), d);
    const std::vector<double> ends2 = {100.0, 1600.0, 14400.0};
    std::array<int, 4> seen{};
    for (int i = 0; i < 200; ++i) {
        // Eyes in every range of the node: about 3, 25, 80 and 400 m from its centre.
        const Mat4 world = r.affine(false);
        const Vec3 center = r.point(1.0);
        const double distance = std::array{3.0, 25.0, 80.0, 400.0}[std::size_t(i % 4)] * r.uniform(0.8, 1.2);
        const Vec3 eye = Vec3(world * Vec4(center, 1.0)) + distance * glm::normalize(r.point(1.0));
        const double scale2 = r.uniform(0.8, 1.2);
        CDouble d2;
        expectTallyMatchesExecuted("lodDistanceSquared", [&](OpTally* hand) {
            d2 = detail::lodDistanceSquared(counted(world), counted(center), counted(eye), CDouble(scale2), hand);
        });
        EXPECT_EQ(d2.value(), detail::lodDistanceSquared(world, center, eye, scale2, nullptr));
        int index = 0;
        expectTallyMatchesExecuted("selectRangeSquared", [&](OpTally* hand) { index = detail::selectRangeSquared(ends2, d2, hand); });
        EXPECT_EQ(index, lod.selectChildSquared(d2.value()));
        ++seen[std::size_t(index + 1)];
    }
    for (int k = 0; k < 4; ++k) EXPECT_GT(seen[std::size_t(k)], 0) << "every child and none are chosen";
}
