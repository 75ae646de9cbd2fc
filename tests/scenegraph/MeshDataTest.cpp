// MeshData validation messages and bounds; MeshDrawable wiring.

#include <gtest/gtest.h>

#include <limits>

#include "throng/scenegraph/MeshDrawable.h"

using namespace throng;

namespace {
std::shared_ptr<MeshData> triangle() {
    auto m = std::make_shared<MeshData>();
    m->name = "tri";
    m->positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
    m->indices = {0, 1, 2};
    return m;
}
void expectInvalid(const MeshData& m, const char* text) {
    try {
        m.validate();
        FAIL() << "accepted a mesh with: " << text;
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("mesh 'tri'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
}
}  // namespace

TEST(MeshData, ValidationNamesTheMeshAndTheProblem) {
    auto m = triangle();
    EXPECT_NO_THROW(m->validate());
    m->indices = {0, 1, 3};
    expectInvalid(*m, "refers to vertex 3");
    m = triangle();
    m->indices = {0, 1};
    expectInvalid(*m, "not a multiple of 3");
    m = triangle();
    m->normals = {{0, 0, 1}};
    expectInvalid(*m, "1 normals for 3 vertices");
    m = triangle();
    m->positions[1].y = std::numeric_limits<float>::quiet_NaN();
    expectInvalid(*m, "position 1 is not finite");
    m = triangle();
    m->joints0 = {{0, 0, 0, 0}};
    expectInvalid(*m, "joints0");
}

TEST(MeshData, BoundHoldsEveryVertexAndDrawableCountsTriangles) {
    auto m = triangle();
    const BoundingSphere b = m->computeBound();
    for (const auto& p : m->positions) EXPECT_TRUE(b.contains(Vec3(p)));
    EXPECT_LT(b.radius(), 1.5);
    MeshDrawable d(m);
    EXPECT_EQ(d.primitiveCount(), 1u);
    EXPECT_EQ(d.name(), "tri");
    EXPECT_THROW(MeshDrawable(nullptr), std::invalid_argument);
}
