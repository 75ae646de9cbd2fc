// Occluder boxes fitted inside analytic solids: a closed box gives itself less the margin, concave
// solids give boxes that stay out of their recesses, open geometry gives nothing, and bad input is
// refused with a message naming the problem. Every fit is also probed with the ray oracle.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "OccluderOracle.h"
#include "throng/scenegraph/AxisBox.h"
#include "throng/scenegraph/MeshShapes.h"
#include "throng/scenegraph/OccluderFitting.h"

using namespace throng;
using throng::testkit::TriangleSoup;

namespace {

// A solid made of the filled cells of a rectilinear lattice (planes xs, ys, zs): its boundary faces,
// counter-clockwise from outside, with faces between filled cells left out. Cells of uneven sizes
// let the solid's walls fall anywhere relative to the fitting grid.
struct Lattice {
    std::vector<float> planes[3];
    std::function<bool(int, int, int)> filled;

    int cells(int a) const { return int(planes[a].size()) - 1; }
    bool at(int x, int y, int z) const {
        if (x < 0 || y < 0 || z < 0 || x >= cells(0) || y >= cells(1) || z >= cells(2)) return false;
        return filled(x, y, z);
    }

    MeshData mesh(const std::string& name) const {
        MeshData m;
        m.name = name;
        for (int z = 0; z < cells(2); ++z)
            for (int y = 0; y < cells(1); ++y)
                for (int x = 0; x < cells(0); ++x) {
                    if (!at(x, y, z)) continue;
                    const int c[3] = {x, y, z};
                    for (int a = 0; a < 3; ++a)
                        for (int side = 0; side < 2; ++side) {
                            int n[3] = {x, y, z};
                            n[a] += side ? 1 : -1;
                            if (at(n[0], n[1], n[2])) continue;
                            addFace(m, c, a, side);
                        }
                }
        return m;
    }

    // The face of cell c on axis a, side (0: low, 1: high), counter-clockwise seen from outside.
    void addFace(MeshData& m, const int c[3], int a, int side) const {
        const int b = (a + 1) % 3, d = (a + 2) % 3;
        const float pa = planes[a][std::size_t(c[a] + side)];
        const float b0 = planes[b][std::size_t(c[b])], b1 = planes[b][std::size_t(c[b] + 1)];
        const float d0 = planes[d][std::size_t(c[d])], d1 = planes[d][std::size_t(c[d] + 1)];
        glm::vec3 q[4];
        const float bs[4] = {b0, b1, b1, b0}, ds[4] = {d0, d0, d1, d1};
        for (int k = 0; k < 4; ++k) {
            q[k][a] = pa;
            q[k][b] = bs[k];
            q[k][d] = ds[k];
        }
        // (b0,d0) (b1,d0) (b1,d1): counter-clockwise about +a since b x d = a.
        const auto base = std::uint32_t(m.positions.size());
        for (const auto& p : q) m.positions.push_back(p);
        if (side == 1) m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        else m.indices.insert(m.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }

    // Whether the closed box lies in the closure of the filled cells: no empty cell meets its interior.
    bool holds(const AxisBox& box) const {
        for (int z = 0; z < cells(2); ++z)
            for (int y = 0; y < cells(1); ++y)
                for (int x = 0; x < cells(0); ++x) {
                    if (at(x, y, z)) continue;
                    const int c[3] = {x, y, z};
                    bool meets = true;
                    for (int a = 0; a < 3; ++a)
                        meets = meets && box.min[a] < planes[a][std::size_t(c[a] + 1)] && box.max[a] > planes[a][std::size_t(c[a])];
                    if (meets) return false;
                }
        for (int a = 0; a < 3; ++a)
            if (box.min[a] < planes[a].front() || box.max[a] > planes[a].back()) return false;
        return true;
    }
};

std::vector<AxisBox> fit(const MeshData& m, const OccluderFitOptions& o = {}, OccluderFitStatistics* s = nullptr) {
    const MeshData* list[] = {&m};
    return fitOccluderBoxes(list, o, s);
}

// The ray oracle on an analytic model: no segment from outside reaches a box without a front face.
void expectHidden(const MeshData& m, const std::vector<AxisBox>& boxes) {
    const MeshData* list[] = {&m};
    const TriangleSoup soup(list);
    const auto report = throng::testkit::probeBoxes(soup, boxes, 3000, 7);
    EXPECT_EQ(report.misses, 0) << m.name << ": " << report.misses << " of " << report.segments << " segments reach a box unseen";
}

bool overlapsOpen(const AxisBox& a, const AxisBox& b) {
    for (int k = 0; k < 3; ++k)
        if (!(a.min[k] < b.max[k] && a.max[k] > b.min[k])) return false;
    return true;
}

std::string expectThrowText(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    ADD_FAILURE() << "no std::invalid_argument";
    return {};
}

}  // namespace

TEST(AxisBox, HelpersMeasureAndNameCorners) {
    const AxisBox b{{1, 2, 3}, {2, 4, 7}};
    EXPECT_FALSE(b.empty());
    EXPECT_EQ(b.size(), glm::vec3(1, 2, 4));
    EXPECT_DOUBLE_EQ(b.volume(), 8.0);
    EXPECT_TRUE(b.contains(glm::vec3(1, 4, 5)));
    EXPECT_FALSE(b.contains(glm::vec3(0.5f, 3, 5)));
    EXPECT_EQ(b.corner(0), b.min);
    EXPECT_EQ(b.corner(7), b.max);
    EXPECT_EQ(b.corner(1), glm::vec3(2, 2, 3));
    EXPECT_EQ(b.corner(2), glm::vec3(1, 4, 3));
    EXPECT_EQ(b.corner(4), glm::vec3(1, 2, 7));
    const AxisBox e{{0, 0, 0}, {1, -1, 1}};
    EXPECT_TRUE(e.empty());
    EXPECT_DOUBLE_EQ(e.volume(), 0.0);
    EXPECT_TRUE(b.contains(e));
    EXPECT_TRUE(b.shrunk(0.6f).empty());
}

TEST(OccluderFitting, ClosedBoxGivesItselfLessTheMargin) {
    const auto box = makeBox("box", glm::vec3(1, 2, 3), glm::vec3(2, 1, 1.5f));
    OccluderFitOptions o;
    o.resolution = 20;
    o.margin = 0.1;
    OccluderFitStatistics s;
    const auto boxes = fit(*box, o, &s);
    ASSERT_EQ(boxes.size(), 1u);
    EXPECT_EQ(s.cells, glm::ivec3(20, 10, 15));
    EXPECT_EQ(s.solidCells, 20u * 10u * 15u);
    const glm::vec3 lo(-1, 1, 1.5f), hi(3, 3, 4.5f);
    for (int a = 0; a < 3; ++a) {
        const float m = float(0.1 * s.cellSize[a]);
        EXPECT_NEAR(boxes[0].min[a], lo[a] + m, 1e-5f) << a;
        EXPECT_NEAR(boxes[0].max[a], hi[a] - m, 1e-5f) << a;
    }
    EXPECT_NEAR(s.boundsVolume, 4.0 * 2.0 * 3.0, 1e-9);
    expectHidden(*box, boxes);
}

TEST(OccluderFitting, LShapeGivesTwoBoxesInside) {
    Lattice l;
    l.planes[0] = {0.0f, 1.37f, 3.0f};
    l.planes[1] = {0.0f, 1.21f, 2.5f};
    l.planes[2] = {0.0f, 1.0f};
    l.filled = [](int x, int y, int) { return !(x == 1 && y == 1); };
    const MeshData m = l.mesh("L");
    OccluderFitStatistics s;
    const auto boxes = fit(m, {}, &s);
    ASSERT_EQ(boxes.size(), 2u);
    double volume = 0.0;
    for (const AxisBox& b : boxes) {
        EXPECT_TRUE(l.holds(b)) << b.min.x << " " << b.min.y << " " << b.max.x << " " << b.max.y;
        volume += b.volume();
    }
    // The two arms of the L, less what the voxels and the margin lose, and counted with overlap.
    const double solid = 3.0 * 2.5 - (3.0 - 1.37) * (2.5 - 1.21);
    EXPECT_GT(volume, 0.8 * solid);
    expectHidden(m, boxes);
}

TEST(OccluderFitting, RecessedWindowStaysEmpty) {
    // A 4 m block with a 1.3 m window recessed 0.45 m into its +z face, and a 6 cm slot (much
    // narrower than a cell) cut 1.7 m deep into its -x face.
    Lattice l;
    l.planes[0] = {0.0f, 1.1f, 2.4f, 4.0f};
    l.planes[1] = {0.0f, 1.3f, 1.36f, 2.2f, 3.5f, 4.0f};
    l.planes[2] = {0.0f, 3.55f, 4.0f};
    auto recess = [](int x, int y, int z) { return x == 1 && (y == 2 || y == 3) && z == 1; };
    auto slot = [](int x, int y, int) { return x == 0 && y == 1; };
    l.filled = [&](int x, int y, int z) { return !recess(x, y, z) && !slot(x, y, z); };
    const MeshData m = l.mesh("window");
    const AxisBox window{{1.1f, 1.36f, 3.55f}, {2.4f, 3.5f, 4.0f}};
    const AxisBox cut{{0.0f, 1.3f, 0.0f}, {1.1f, 1.36f, 4.0f}};
    for (int resolution : {8, 16, 33, 64}) {
        OccluderFitOptions o;
        o.resolution = resolution;
        o.maxBoxes = 8;
        o.minGain = 0.01;
        const auto boxes = fit(m, o);
        EXPECT_FALSE(boxes.empty()) << resolution;
        for (const AxisBox& b : boxes) {
            EXPECT_FALSE(overlapsOpen(b, window)) << resolution;
            EXPECT_FALSE(overlapsOpen(b, cut)) << resolution;
            EXPECT_TRUE(l.holds(b)) << resolution;
        }
        expectHidden(m, boxes);
    }
}

TEST(OccluderFitting, CupHollowStaysEmpty) {
    // A thick-walled cup (closed surface, hollow open at the top) and a thin one (an open mesh:
    // a box without its top face), whose inside is seen from above.
    Lattice l;
    l.planes[0] = {0.0f, 0.3f, 1.7f, 2.0f};
    l.planes[1] = {0.0f, 0.4f, 2.0f};
    l.planes[2] = {0.0f, 0.25f, 1.75f, 2.0f};
    l.filled = [](int x, int y, int z) { return !(x == 1 && z == 1 && y == 1); };
    const MeshData cup = l.mesh("cup");
    const AxisBox hollow{{0.3f, 0.4f, 0.25f}, {1.7f, 2.0f, 1.75f}};
    OccluderFitOptions o;
    o.resolution = 40;
    o.maxBoxes = 8;
    o.minGain = 0.01;
    const auto boxes = fit(cup, o);
    EXPECT_FALSE(boxes.empty());
    for (const AxisBox& b : boxes) {
        EXPECT_FALSE(overlapsOpen(b, hollow));
        EXPECT_TRUE(l.holds(b));
    }
    expectHidden(cup, boxes);

    MeshData thin = *makeBox("thin cup", glm::vec3(0), glm::vec3(1));
    // Drop the two triangles of the top face.
    MeshData open = thin;
    open.indices.clear();
    for (std::size_t t = 0; t < thin.indices.size() / 3; ++t) {
        const glm::vec3 c = (thin.positions[thin.indices[3 * t]] + thin.positions[thin.indices[3 * t + 1]] + thin.positions[thin.indices[3 * t + 2]]) / 3.0f;
        if (c.y > 0.99f) continue;
        open.indices.insert(open.indices.end(), thin.indices.begin() + std::ptrdiff_t(3 * t), thin.indices.begin() + std::ptrdiff_t(3 * t + 3));
    }
    ASSERT_EQ(open.indices.size(), thin.indices.size() - 6);
    EXPECT_TRUE(fit(open).empty());
}

TEST(OccluderFitting, OpenInvertedOrEmptyGeometryGivesNoBox) {
    MeshData quad;
    quad.name = "quad";
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2f}, {0, 1, 0.2f}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    OccluderFitStatistics s;
    EXPECT_TRUE(fit(quad, {}, &s).empty());
    EXPECT_EQ(s.solidCells, 0u);
    // A flat quad: the bounding box has no volume.
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    EXPECT_TRUE(fit(quad).empty());
    // A box turned inside out (clockwise from outside) encloses nothing the renderer draws.
    MeshData inverted = *makeBox("inverted", glm::vec3(0), glm::vec3(1));
    for (std::size_t i = 0; i < inverted.indices.size(); i += 3) std::swap(inverted.indices[i + 1], inverted.indices[i + 2]);
    EXPECT_TRUE(fit(inverted).empty());
    // Nothing at all.
    EXPECT_TRUE(fitOccluderBoxes({}).empty());
    MeshData none;
    none.positions = {{0, 0, 0}};
    EXPECT_TRUE(fit(none).empty());
}

TEST(OccluderFitting, OverlappingClosedPartsFillTheirUnion) {
    // Two closed boxes that overlap (as modelling tools leave them): the union is solid.
    const auto a = makeBox("a", glm::vec3(0), glm::vec3(2, 1, 1));
    const auto b = makeBox("b", glm::vec3(1.5f, 1.2f, 0.1f), glm::vec3(0.8f, 1.5f, 0.7f));
    const MeshData* list[] = {a.get(), b.get()};
    OccluderFitOptions o;
    o.maxBoxes = 4;
    const auto boxes = fitOccluderBoxes(list, o);
    ASSERT_GE(boxes.size(), 2u);
    const AxisBox ba{{-2, -1, -1}, {2, 1, 1}}, bb{{0.7f, -0.3f, -0.6f}, {2.3f, 2.7f, 0.8f}};
    for (const AxisBox& box : boxes) {
        // Inside one of the parts or, straddling both, inside their union along every axis.
        for (int c = 0; c < 8; ++c) EXPECT_TRUE(ba.contains(box.corner(c)) || bb.contains(box.corner(c)));
    }
    // Faces of one part inside the other split the solid: the first box takes most of the larger part.
    EXPECT_GT(boxes[0].volume(), 0.6 * ba.volume());
    const TriangleSoup soup(list);
    const auto report = throng::testkit::probeBoxes(soup, boxes, 3000, 11);
    EXPECT_EQ(report.misses, 0);
}

TEST(OccluderFitting, BadOptionsAndMeshesAreNamed) {
    const auto box = makeBox("box", glm::vec3(0), glm::vec3(1));
    auto withOption = [&](auto set) {
        OccluderFitOptions o;
        set(o);
        return expectThrowText([&] { fit(*box, o); });
    };
    EXPECT_NE(withOption([](auto& o) { o.resolution = 1; }).find("resolution"), std::string::npos);
    EXPECT_NE(withOption([](auto& o) { o.resolution = 100000; }).find("resolution"), std::string::npos);
    EXPECT_NE(withOption([](auto& o) { o.maxBoxes = 0; }).find("maxBoxes"), std::string::npos);
    EXPECT_NE(withOption([](auto& o) { o.minGain = -0.1; }).find("minGain"), std::string::npos);
    EXPECT_NE(withOption([](auto& o) { o.minGain = std::nan(""); }).find("minGain"), std::string::npos);
    EXPECT_NE(withOption([](auto& o) { o.margin = 0.0; }).find("margin"), std::string::npos);
    EXPECT_NE(withOption([](auto& o) { o.margin = 0.7; }).find("margin"), std::string::npos);

    MeshData bad = *box;
    bad.name = "wall";
    bad.positions[5].z = std::numeric_limits<float>::quiet_NaN();
    const MeshData* list[] = {box.get(), &bad};
    std::string what = expectThrowText([&] { fitOccluderBoxes(list); });
    EXPECT_NE(what.find("mesh 1 ('wall')"), std::string::npos) << what;
    EXPECT_NE(what.find("vertex 5 is not finite"), std::string::npos) << what;

    bad = *box;
    bad.indices[7] = 999;
    list[1] = &bad;
    what = expectThrowText([&] { fitOccluderBoxes(list); });
    EXPECT_NE(what.find("mesh 1"), std::string::npos) << what;
    EXPECT_NE(what.find("index 7 refers to vertex 999"), std::string::npos) << what;

    bad = *box;
    bad.indices.pop_back();
    what = expectThrowText([&] { fitOccluderBoxes(list); });
    EXPECT_NE(what.find("not a multiple of 3"), std::string::npos) << what;

    list[0] = nullptr;
    what = expectThrowText([&] { fitOccluderBoxes(list); });
    EXPECT_NE(what.find("mesh 0 is null"), std::string::npos) << what;
}
