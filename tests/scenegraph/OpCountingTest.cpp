// FMULT accounting: exact costs of the counted primitives, and exact NO_xx counts of a traversal.

#include <gtest/gtest.h>

#include <numbers>

#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/scenegraph/TraditionalProcessor.h"
#include "throng/scenegraph/Transform.h"

using namespace throng;

namespace {
OpTally tally(std::uint64_t m, std::uint64_t a, std::uint64_t d = 0, std::uint64_t s = 0) {
    OpTally t;
    t.mults = m;
    t.adds = a;
    t.divs = d;
    t.sqrts = s;
    return t;
}
}  // namespace

TEST(OpCounting, UnitCostsAreThoseOfTheCostModel) {
    OpTally t;
    t.mults = 1;
    EXPECT_EQ(t.fmult(), 1u);
    t = OpTally{};
    t.adds = 1;
    EXPECT_EQ(t.fmult(), 1u);
    t = OpTally{};
    t.divs = 1;
    EXPECT_EQ(t.fmult(), 5u);
    t = OpTally{};
    t.sqrts = 1;
    EXPECT_EQ(t.fmult(), 7u);
    t = OpTally{};
    t.gpuMatrixProducts = 1;
    EXPECT_EQ(t.fmult(), 10u);
}

TEST(OpCounting, ExactCostsOfPrimitives) {
    if (!OpCounter::compiledIn()) GTEST_SKIP() << "counting compiled out";
    OpTally ops;
    composeAffine(Mat4(1.0), Mat4(1.0), &ops);
    EXPECT_EQ(ops, tally(36, 27));
    EXPECT_EQ(ops.fmult(), 63u);

    ops = {};
    matrixFromDofs(TransformDofs{}, &ops);
    EXPECT_EQ(ops.fmult(), 33u);

    ops = {};
    BoundingSphere(Vec3(1, 2, 3), 1).transformed(Mat4(2.0), &ops);
    EXPECT_EQ(ops, tally(29, 33, 0, 1));  // centre 9+9, scale bound 18+20+sqrt, radius 1, padding 1+4
    EXPECT_EQ(ops.fmult(), 69u);

    ops = {};
    BoundingSphere a(Vec3(0.0), 1);
    a.expandBy(BoundingSphere(Vec3(5, 0, 0), 1), &ops);  // disjoint: full merge
    EXPECT_EQ(ops, tally(8, 19, 1, 1));
    EXPECT_EQ(ops.fmult(), 39u);
    ops = {};
    a.expandBy(BoundingSphere(Vec3(1, 0, 0), 0.5), &ops);  // already inside: first test only
    EXPECT_EQ(ops.fmult(), 17u);

    Camera cam;
    cam.setPerspective(std::numbers::pi / 2, 1.0, 1.0, 100.0);
    cam.setLookAt(Vec3(0.0), Vec3(0, 0, -1), Vec3(0, 1, 0));
    const Frustum f = cam.frustum();
    ops = {};
    PlaneMask mask = Frustum::kAllPlanes;
    f.classify(BoundingSphere(Vec3(0, 0, -50), 1), mask, &ops);  // inside all six planes
    EXPECT_EQ(ops, tally(18, 30));
    EXPECT_EQ(ops.fmult(), 48u);
    ops = {};
    mask = Frustum::kAllPlanes;
    f.classify(BoundingSphere(Vec3(-100, 0, -50), 1), mask, &ops);  // outside the first (left) plane
    EXPECT_EQ(ops, tally(3, 4));
}

TEST(OpCounting, TraversalCountsOperationsPerCategory) {
    if (!OpCounter::compiledIn()) GTEST_SKIP() << "counting compiled out";
    // root -> 10 x (Transform -> LOD -> {Geometry, Geometry}), all in view.
    auto root = std::make_shared<Group>();
    auto drawable = std::make_shared<Drawable>("d", BoundingSphere(Vec3(0.0), 0.5), 10);
    std::vector<Transform*> transforms;
    for (int i = 0; i < 10; ++i) {
        auto t = std::make_shared<Transform>();
        TransformDofs d;
        d.translation = Vec3(i - 5.0, 0, -30);
        t->setDofs(d);
        auto lod = std::make_shared<LOD>();
        lod->addChild(std::make_shared<Geometry>(drawable), 100);
        lod->addChild(std::make_shared<Geometry>(drawable), 200);
        t->addChild(lod);
        root->addChild(t);
        transforms.push_back(t.get());
    }
    Camera cam;
    cam.setPerspective(std::numbers::pi / 2, 1.0, 1.0, 100.0);
    cam.setLookAt(Vec3(0.0), Vec3(0, 0, -1), Vec3(0, 1, 0));

    TraditionalProcessor proc;
    proc.counter().setEnabled(true);
    proc.processFrame(*root, cam, 0.0);
    const OpCounter& c = proc.counter();
    EXPECT_EQ(c.operations(OpCategory::SkeletonMatrix), 10u);     // one world matrix per Transform
    EXPECT_EQ(c.fmult(OpCategory::SkeletonMatrix), 10u * (33 + 63));
    EXPECT_EQ(c.operations(OpCategory::BsphereRecompute), 10u * 4 + 1);  // 2 leaves, LOD, Transform; root
    EXPECT_EQ(c.operations(OpCategory::BsphereFrustumTest), 1u) << "the root is inside every plane";
    EXPECT_EQ(c.fmult(OpCategory::BsphereFrustumTest), 48u);
    EXPECT_EQ(c.operations(OpCategory::LodDistance), 10u);
    EXPECT_EQ(c.fmult(OpCategory::LodDistance), 10u * (13 + 14 + 1));
    EXPECT_EQ(c.operations(OpCategory::RefpointMatrix), 0u);
    EXPECT_EQ(proc.statistics().fmultTotal, c.totalFmult());

    // A static frame composes nothing; moving one Transform costs one matrix.
    proc.processFrame(*root, cam, 0.1);
    EXPECT_EQ(c.operations(OpCategory::SkeletonMatrix), 0u);
    EXPECT_EQ(c.operations(OpCategory::BsphereRecompute), 0u);
    TransformDofs d = transforms[3]->dofs();
    d.translation.y = 1.0;
    transforms[3]->setDofs(d);
    proc.processFrame(*root, cam, 0.2);
    EXPECT_EQ(c.operations(OpCategory::SkeletonMatrix), 1u);
    EXPECT_EQ(c.operations(OpCategory::BsphereRecompute), 5u);  // its 2 leaves, LOD, itself, root

    // Disabled counting records nothing.
    proc.counter().setEnabled(false);
    proc.processFrame(*root, cam, 0.3);
    EXPECT_EQ(proc.statistics().fmultTotal, 0u);
    EXPECT_EQ(c.totalFmult(), 0u);
}
