// FMULT accounting: the unit costs, and a traversal's NO_xx counts and FMULT per category. The
// FMULT expected of each category is what the kernels execute on an operation-counting number type
// for the same inputs (tests/counting checks each kernel's own tally), so the test checks that the
// traversal charges the right work to the right category, not a restated constant.

#include <gtest/gtest.h>

#include <numbers>

#include "CountedScalar.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/scenegraph/TraditionalProcessor.h"
#include "throng/scenegraph/Transform.h"
#include "throng/scenegraph/detail/BoundingSphereImpl.h"
#include "throng/scenegraph/detail/FrustumKernel.h"
#include "throng/scenegraph/detail/LodKernels.h"
#include "throng/scenegraph/detail/TransformKernels.h"

using namespace throng;
using namespace throng::counting;

namespace {
using CVec3 = glm::vec<3, CDouble>;
using CMat4 = glm::mat<4, 4, CDouble>;
}  // namespace

TEST(OpCounting, UnitCostsAreThoseOfTheCostModel) {
    // One operation of each kind costs what the cost model charges it, in FMULT.
    const std::pair<std::uint64_t OpTally::*, std::uint64_t> costs[] = {
        {&OpTally::mults, 1}, {&OpTally::adds, 1}, {&OpTally::divs, 5}, {&OpTally::sqrts, 7}, {&OpTally::gpuMatrixProducts, 10}};
    for (const auto& [kind, fmult] : costs) {
        OpTally t;
        t.*kind = 1;
        EXPECT_EQ(t.fmult(), fmult);
    }
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

    // What each Transform, the root's frustum test and each LOD node execute.
    const Mat4 local = transforms[0]->localMatrix();
    const std::uint64_t matrix =
        executedBy([&] {
            (void)detail::matrixFromDofs(CVec3(transforms[0]->dofs().translation), glm::qua<CDouble>(transforms[0]->dofs().rotation),
                                         CVec3(transforms[0]->dofs().scale), nullptr);
            (void)detail::composeAffine(CMat4(1.0), CMat4(local), nullptr);
        }).fmult();
    std::array<glm::vec<4, CDouble>, Frustum::kPlaneCount> planes;
    for (int i = 0; i < Frustum::kPlaneCount; ++i) planes[std::size_t(i)] = glm::vec<4, CDouble>(cam.frustum().plane(i));
    PlaneMask mask = cam.frustum().activePlanes();
    const std::uint64_t rootTest =
        executedBy([&] { (void)detail::classifySphere(planes, BasicBoundingSphere<CDouble>(root->worldBound()), mask, nullptr); }).fmult();
    ASSERT_EQ(mask, 0) << "the root is inside every plane";
    std::uint64_t lodDistances = 0;
    const std::vector<double> ends2 = {100.0 * 100.0, 200.0 * 200.0};
    for (Transform* t : transforms)
        lodDistances += executedBy([&] {
                            const CDouble d2 = detail::lodDistanceSquared(CMat4(t->worldMatrix()), CVec3(0.0), CVec3(cam.eye()), CDouble(1.0), nullptr);
                            (void)detail::selectRangeSquared(ends2, d2, nullptr);
                        }).fmult();

    EXPECT_EQ(c.operations(OpCategory::SkeletonMatrix), 10u);     // one world matrix per Transform
    EXPECT_EQ(c.fmult(OpCategory::SkeletonMatrix), 10u * matrix);
    EXPECT_EQ(c.operations(OpCategory::BsphereRecompute), 10u * 4 + 1);  // 2 leaves, LOD, Transform; root
    EXPECT_EQ(c.operations(OpCategory::BsphereFrustumTest), 1u) << "the root is inside every plane";
    EXPECT_EQ(c.fmult(OpCategory::BsphereFrustumTest), rootTest);
    EXPECT_EQ(c.operations(OpCategory::LodDistance), 10u);
    EXPECT_EQ(c.fmult(OpCategory::LodDistance), lodDistances);
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
