// The CPU half of GlRenderer::draw without a GL context (render/src/DrawPlan.h): the drawing order
// and distance bands, which items share an instanced draw, and the instance record an item gets.

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "DrawPlan.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"

using namespace throng;
using namespace throng::detail;

namespace {

// A unit box (radius sqrt(3)) at `x` metres along X, as a draw item.
DrawItem boxAt(const MeshDrawable& box, double x) {
    DrawItem item;
    item.drawable = &box;
    item.world.translation = Vec3(x, 0.0, 0.0);
    return item;
}

std::vector<const DrawItem*> pointers(const std::vector<DrawItem>& items) {
    std::vector<const DrawItem*> out;
    for (const DrawItem& i : items) out.push_back(&i);
    return out;
}

}  // namespace

TEST(DrawPlan, DistanceBandsDoubleInDepthAndSwallowNonFiniteDistances) {
    EXPECT_EQ(distanceBand(0.0f), 0);
    EXPECT_EQ(distanceBand(15.9f), 0);
    EXPECT_EQ(distanceBand(16.0f), 1);
    EXPECT_EQ(distanceBand(31.9f), 1);
    EXPECT_EQ(distanceBand(32.0f), 2);
    EXPECT_EQ(distanceBand(std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ(distanceBand(std::numeric_limits<float>::infinity()), distanceBand(1e30f));
    EXPECT_EQ(distanceBand(-5.0f), 0);
}

TEST(DrawPlan, FrontToBackOrdersByTheNearestPointAndKeepsListOrderOnTies) {
    const MeshDrawable box(makeBox("box", glm::vec3(0.0f), glm::vec3(1.0f), glm::vec4(1.0f)));
    std::vector<DrawItem> items{boxAt(box, 100.0), boxAt(box, 10.0), boxAt(box, 40.0), boxAt(box, 10.0)};
    items.push_back(DrawItem{});  // no drawable: counts as at the eye
    DrawOrder order;
    order.plan(pointers(items), Vec3(0.0), false);
    EXPECT_EQ(order.order(), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
    EXPECT_EQ(order.band(), (std::vector<std::int32_t>{0, 0, 0, 0, 0})) << "no bands without front-to-back";
    order.plan(pointers(items), Vec3(0.0), true);
    EXPECT_EQ(order.order(), (std::vector<std::uint32_t>{4, 1, 3, 2, 0}));
    // Nearest points: 100 - sqrt(3), 10 - sqrt(3), 40 - sqrt(3).
    EXPECT_EQ(order.band()[0], distanceBand(float(100.0 - std::sqrt(3.0))));
    EXPECT_EQ(order.band()[1], 0);
    EXPECT_EQ(order.band()[2], 2);
}

TEST(DrawPlan, ItemsShareABatchOnlyWithTheSameMeshVariantAndBand) {
    BatchPlanner planner;
    BatchSlots meshA, meshB;
    bool opened = false;
    planner.begin(true);
    const std::uint32_t a0 = planner.join(meshA, 0, 0, opened);
    EXPECT_TRUE(opened);
    EXPECT_EQ(planner.join(meshA, 0, 0, opened), a0);
    EXPECT_FALSE(opened);
    const std::uint32_t b0 = planner.join(meshB, 0, 0, opened);  // another mesh
    EXPECT_TRUE(opened);
    const std::uint32_t aMirrored = planner.join(meshA, 1, 0, opened);  // the other winding
    EXPECT_TRUE(opened);
    const std::uint32_t aFar = planner.join(meshA, 0, 3, opened);  // another band: a new batch, now the open one
    EXPECT_TRUE(opened);
    EXPECT_EQ(planner.join(meshA, 0, 3, opened), aFar);
    const std::uint32_t alone = planner.alone(0);
    EXPECT_EQ((std::vector<std::uint32_t>{a0, b0, aMirrored, aFar, alone}), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}))
        << "batches are numbered in order of first appearance";
    ASSERT_EQ(planner.layOut(), 7u);
    const auto& b = planner.batches();
    EXPECT_EQ(b[0].count, 2u);
    EXPECT_EQ(b[3].count, 2u);
    EXPECT_EQ(b[1].first, 2u);
    EXPECT_EQ(b[4].first, 6u);
    EXPECT_EQ(planner.nextSlot(0), 0u);
    EXPECT_EQ(planner.nextSlot(0), 1u);
    EXPECT_EQ(planner.nextSlot(3), 4u);
    // A new draw forgets the last draw's batches without touching the meshes' records.
    planner.begin(true);
    EXPECT_EQ(planner.join(meshA, 0, 3, opened), 0u);
    EXPECT_TRUE(opened);
}

TEST(DrawPlan, WithoutInstancingEveryItemIsADrawOfItsOwn) {
    BatchPlanner planner;
    BatchSlots mesh;
    bool opened = false;
    planner.begin(false);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(planner.join(mesh, 0, 0, opened), std::uint32_t(i));
        EXPECT_TRUE(opened);
    }
    EXPECT_EQ(planner.layOut(), 3u);
}

// Stability: a crowd a thousand kilometres from the world origin keeps millimetres. The model
// matrix is made eye-relative in double before it is rounded, so what the GPU gets is small.
TEST(DrawPlan, AnInstanceFarFromTheOriginKeepsItsPositionRelativeToTheEye) {
    DrawItem item;
    item.world.translation = Vec3(1e6 + 0.0012, 2.0, -1e6 - 0.0034);
    item.world.linear = glm::mat3(2.0f);
    item.tint = glm::vec4(0.1f, 0.2f, 0.3f, 0.4f);
    InstanceData d;
    d.paletteBase = 7;
    writeInstance(d, item, Vec3(1e6, 0.0, -1e6));
    EXPECT_NEAR(d.model[12], 0.0012f, 1e-7f);
    EXPECT_NEAR(d.model[13], 2.0f, 1e-7f);
    EXPECT_NEAR(d.model[14], -0.0034f, 1e-7f);
    EXPECT_EQ(d.model[15], 1.0f);
    EXPECT_EQ(d.model[0], 2.0f);
    EXPECT_EQ(d.model[3], 0.0f);
    EXPECT_EQ(d.tint[3], 0.4f);
    EXPECT_EQ(d.paletteBase, 0) << "palette fields are the caller's, per path";
    // Rounded to float first, the same position would be off by centimetres.
    EXPECT_GT(std::abs(float(1e6 + 0.0012) - float(1e6) - 0.0012f), 1e-3f);
}
