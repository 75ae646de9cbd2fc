// Edge cases and bad input of the feature, proxy and view warps: degenerate capsules and extreme
// depths stay finite, degenerate proxy triangles draw nothing, and every bad argument is refused
// with a message naming the problem.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "ImpostorTestSupport.h"
#include "throng/render/FeatureTrack.h"
#include "throng/render/GpuMorpher.h"
#include "throng/render/LimbMorph.h"
#include "throng/render/MorphFeatures.h"
#include "throng/render/ProxyMesh.h"
#include "throng/render/ProxyWarp.h"
#include "throng/render/ViewWarp.h"

namespace throng {
namespace {

using test::BakedHumanoid;

// Expects `f` to throw std::invalid_argument whose message contains `text`.
template <class F>
void expectRefused(F&& f, const std::string& text) {
    try {
        f();
        ADD_FAILURE() << "no exception; expected one mentioning '" << text << "'";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(ImpostorWarpStability, DegenerateCapsulesAndExtremeDepthsStayFinite) {
    const std::vector<FeatureLine> dst{{{10, 10}, {10, 10}}, {{5, 5}, {30, 5}}}, src{{{12, 10}, {12, 10}}, {{5, 8}, {30, 8}}};
    std::vector<LineAttributes> a(2);
    a[0].radius = 50.0f;  // a point feature with a huge capsule
    a[1].radius = 1e30f;
    a[0].depthP = a[0].depthQ = 1e30f;  // clamped exponent
    a[1].depthP = -1e30f;
    MorphParameters p;
    p.depth = 1e6f;
    for (const glm::vec2 x : {glm::vec2(10, 10), glm::vec2(-1e7f, 3e7f), glm::vec2(20, 5)}) {
        const glm::vec2 s = beierNeelySourcePosition(x, dst, src, p, a);
        EXPECT_TRUE(std::isfinite(s.x) && std::isfinite(s.y)) << x.x << " " << x.y;
    }
    // Every weight zero: no displacement at all.
    std::vector<LineAttributes> none(2);
    none[0].weight = none[1].weight = 0.0f;
    EXPECT_EQ(beierNeelySourcePosition({7, 9}, dst, src, {}, none), glm::vec2(7, 9));
}

TEST(ImpostorWarpStability, BadLineAttributesAreRefused) {
    const ImpostorAtlas& atlas = *BakedHumanoid::get().full;
    const Image a = atlas.cell(0, 0);
    const std::vector<FeatureLine> lines{{{10, 10}, {20, 20}}};
    std::vector<LineAttributes> two(2), bad(1);
    expectRefused([&] { morphImages(a, lines, a, lines, lines, 0.5f, {}, 1, two); }, "2 line attributes for 1 lines");
    bad[0].radius = -1.0f;
    expectRefused([&] { morphImages(a, lines, a, lines, lines, 0.5f, {}, 1, bad); }, "negative");
    bad[0] = {};
    bad[0].weight = kNaN;
    expectRefused([&] { morphImages(a, lines, a, lines, lines, 0.5f, {}, 1, bad); }, "not finite");
    MorphParameters p;
    p.depth = kNaN;
    expectRefused([&] { morphImages(a, lines, a, lines, lines, 0.5f, p); }, "depth");
    GpuMorpher gpu(BakedHumanoid::get().context);
    expectRefused([&] { gpu.morph(a, lines, a, lines, lines, 0.5f, {}, two); }, "GpuMorpher::morph");
}

TEST(ImpostorWarpStability, TrackRefusesBadInput) {
    expectRefused([] { FeatureTrack(2, 0, glm::vec3(0), 1.0f, 64); }, "key-frame");
    expectRefused([] { FeatureTrack(2, 4, glm::vec3(0), 0.0f, 64); }, "radius");
    expectRefused([] { FeatureTrack(2, 4, glm::vec3(kNaN), 1.0f, 64); }, "centre");
    FeatureTrack t(2, 4, glm::vec3(0), 1.0f, 64);
    const std::vector<glm::vec3> one(1), two(2), nan(2, glm::vec3(kNaN));
    expectRefused([&] { t.setJoints(0, one, two); }, "1 and 2 joints for 2 bones");
    expectRefused([&] { t.setJoints(4, two, two); }, "key-frame 4");
    expectRefused([&] { t.setJoints(0, two, nan); }, "not finite");
    expectRefused([&] { t.setRadii({1.0f}); }, "1 radii");
    expectRefused([&] { t.setRadii({1.0f, -2.0f}); }, "radius 1");
    expectRefused([&] { t.setTopology({}, {}); }, "setTopology");
    expectRefused([&] { t.lines(0, {0, 1, 0}); }, "vertical");
    expectRefused([&] { t.lines(0, {0, 0, 0}); }, "zero");
    expectRefused([&] { t.lines(9, {0, 0, 1}); }, "key-frame 9");
    EXPECT_FALSE(t.related(0, 7)) << "a bone outside the track is related to nothing";
    EXPECT_TRUE(t.related(1, 1));
}

TEST(ImpostorWarpStability, FeaturesRefuseMismatches) {
    BakedHumanoid& b = BakedHumanoid::get();
    ImpostorAtlas half = *b.full;
    half.dropOddKeyframes();
    const FeatureTrack track = b.baker->featureTrack();
    expectRefused([&] { droppedCellFeatures(half, track, 0, 2, {}); }, "stored");
    expectRefused([&] { droppedCellFeatures(half, track, 9999, 1, {}); }, "view 9999");
    expectRefused([&] { droppedCellFeatures(half, FeatureTrack(3, 8, glm::vec3(0), 1.0f, 64), 0, 1, {}); }, "does not match");
    std::vector<FeatureLine> lines;
    std::vector<LineAttributes> attributes;
    const std::uint32_t bones[1] = {500};
    expectRefused([&] { viewFeatures(track, 0, {0, 0, 1}, bones, std::vector<float>(track.boneCount(), 1.0f), {}, lines, attributes); }, "bone 500");
    expectRefused([&] { viewFeatures(track, 0, {0, 0, 1}, {}, std::vector<float>(1, 1.0f), {}, lines, attributes); }, "weights for");
    CellFeatures f = droppedCellFeatures(half, track, 0, 1, {});
    f.bones.pop_back();
    const Image a = half.cell(0, 0);
    expectRefused([&] { morphLimbs(a, a, f, track, 0.5f); }, "differ in size");
    f = droppedCellFeatures(half, track, 0, 1, {});
    VisibilityOptions v;
    v.distrust = 2.0f;
    expectRefused([&] { morphLimbs(a, a, f, track, 0.5f, {}, v); }, "distrust");
}

TEST(ImpostorWarpStability, ProxyRefusesBadInputAndSkipsDegenerateTriangles) {
    expectRefused([] { ProxyMesh(3, 0, glm::vec3(0), 1.0f, 16); }, "key-frame");
    ProxyMesh m(3, 2, glm::vec3(0), 1.0f, 16);
    expectRefused([&] { m.setTriangles({{0, 1, 3}}); }, "vertex 3 of 3");
    const std::vector<glm::vec3> nan(3, glm::vec3(kNaN)), two(2);
    expectRefused([&] { m.setPositions(0, nan); }, "not finite");
    expectRefused([&] { m.setPositions(0, two); }, "2 positions for 3");
    expectRefused([&] { m.setPositions(2, nan); }, "key-frame 2");
    // A triangle collapsed to a line draws nothing, and its normals are zero rather than NaN.
    m.setPositions(0, std::vector<glm::vec3>{{0, 0, 0}, {0.5f, 0, 0}, {1, 0, 0}});
    m.setTriangles({{0, 1, 2}});
    for (const glm::vec3& n : m.normals(0)) EXPECT_EQ(n, glm::vec3(0.0f));
    Image cell;
    cell.width = cell.height = 16;
    cell.rgba.assign(16 * 16 * 4, 255);
    const ProxySource one[1] = {{&cell, {0, 0, 1}, 0, 1.0f}};
    const Image out = warpProxy(m, one, {0, 0, 1}, 0);
    for (std::size_t i = 3; i < out.rgba.size(); i += 4) EXPECT_EQ(out.rgba[i], 0);

    expectRefused([&] { warpProxy(m, {}, {0, 0, 1}, 0); }, "no source");
    const ProxySource null[1] = {{nullptr, {0, 0, 1}, 0, 1.0f}};
    expectRefused([&] { warpProxy(m, null, {0, 0, 1}, 0); }, "missing");
    Image small = cell;
    small.width = small.height = 8;
    small.rgba.resize(8 * 8 * 4);
    const ProxySource wrong[1] = {{&small, {0, 0, 1}, 0, 1.0f}};
    expectRefused([&] { warpProxy(m, wrong, {0, 0, 1}, 0); }, "16 pixels square");
    const ProxySource negative[1] = {{&cell, {0, 0, 1}, 0, -1.0f}};
    expectRefused([&] { warpProxy(m, negative, {0, 0, 1}, 0); }, "negative");
    const ProxySource zero[1] = {{&cell, {0, 0, 1}, 0, 0.0f}};
    expectRefused([&] { warpProxy(m, zero, {0, 0, 1}, 0); }, "sum to zero");
    const ProxySource late[1] = {{&cell, {0, 0, 1}, 5, 1.0f}};
    expectRefused([&] { warpProxy(m, late, {0, 0, 1}, 0); }, "key-frame");
    expectRefused([&] { warpProxy(m, one, {0, 0, 1}, std::numeric_limits<double>::infinity()); }, "not finite");
    ProxyWarpOptions o;
    o.distrust = 3.0f;
    expectRefused([&] { warpProxy(m, one, {0, 0, 1}, 0, o); }, "distrust");
    expectRefused([&] { warpProxy(m, one, {0, 1, 0}, 0); }, "vertical");
}

TEST(ImpostorWarpStability, ViewWarpsRefuseMismatches) {
    const std::vector<std::vector<FeatureLine>> two{{{{0, 0}, {1, 1}}}, {{{0, 0}, {1, 1}}, {{2, 2}, {3, 3}}}};
    const float w2[2] = {0.5f, 0.5f}, w1[1] = {1.0f};
    expectRefused([&] { blendViewLines(two, w1); }, "2 views and 1 weights");
    expectRefused([&] { blendViewLines(two, w2); }, "different line counts");
    const glm::vec3 dirs[2] = {{0, 0, 1}, {1, 0, 0}};
    expectRefused([&] { viewPostwarp(dirs, w1, {0, 0, 1}); }, "2 views and 1 weights");
    expectRefused([&] { viewPostwarp(dirs, w2, {0, 1, 0}); }, "vertical");
    const ImpostorAtlas& atlas = *BakedHumanoid::get().full;
    const std::vector<Image> cells{atlas.cell(0, 0), atlas.cell(1, 0)};
    const std::vector<std::vector<FeatureLine>> same{{{{0, 0}, {1, 1}}}, {{{0, 0}, {1, 1}}}};
    const std::vector<FeatureLine> target{{{0, 0}, {1, 1}}};
    expectRefused([&] { warpViews(cells, same, w1, target); }, "2 cells, 2 line sets, 1 weights");
    const float bad[2] = {0.5f, kNaN};
    expectRefused([&] { warpViews(cells, same, bad, target); }, "not finite");
    const float none[2] = {0.0f, 0.0f};
    expectRefused([&] { warpViews(cells, same, none, target); }, "sum to zero");
    expectRefused([&] { warpViews(cells, two, w2, target); }, "target lines");
}

}  // namespace
}  // namespace throng
