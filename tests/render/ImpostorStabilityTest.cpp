// Impostor edge cases give finite, sensible images: zero-length and coincident feature lines, the
// eye exactly on a baked view, at the pole and below the hemisphere's rim.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "ImpostorTestSupport.h"
#include "throng/render/GpuMorpher.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/render/MorphCache.h"
#include "throng/render/ViewHemisphere.h"

namespace throng {
namespace {

using test::BakedHumanoid;

void expectSensibleBlend(const ViewBlend& b, const ViewHemisphere& h) {
    float sum = 0;
    for (int i = 0; i < 3; ++i) {
        EXPECT_TRUE(std::isfinite(b.weights[i]));
        EXPECT_GE(b.weights[i], 0.0f);
        EXPECT_LT(b.views[i], h.viewCount());
        sum += b.weights[i];
    }
    EXPECT_NEAR(sum, 1.0f, 1e-5f);
}

TEST(ImpostorStability, EyeOnABakedViewUsesThatViewAlone) {
    const ViewHemisphere h;
    for (std::uint32_t v = 0; v < h.viewCount(); ++v)
        for (bool smooth : {false, true}) {
            const ViewBlend b = h.blend(h.direction(v) * 3.0f, smooth);
            expectSensibleBlend(b, h);
            float w = 0;
            for (int i = 0; i < 3; ++i)
                if (b.views[i] == v) w += b.weights[i];
            EXPECT_NEAR(w, 1.0f, 1e-4f) << "view " << v;
            EXPECT_EQ(h.nearest(h.direction(v)), v);
        }
}

TEST(ImpostorStability, PoleRimAndDegenerateDirections) {
    const ViewHemisphere h;
    const glm::vec3 pole(0, 1, 0), below(0.3f, -0.9f, 0.2f), rim(1, 0, 0);
    for (bool smooth : {false, true}) {
        const ViewBlend top = h.blend(pole, smooth);
        expectSensibleBlend(top, h);
        for (int i = 0; i < 3; ++i)
            if (top.weights[i] > 0) {
                EXPECT_EQ(top.views[i] / 16, 3u) << "the pole uses the top ring";
            }
        const ViewBlend under = h.blend(below, smooth);
        expectSensibleBlend(under, h);
        for (int i = 0; i < 3; ++i)
            if (under.weights[i] > 0) {
                EXPECT_EQ(under.views[i] / 16, 0u) << "below the rim uses the bottom ring";
            }
        expectSensibleBlend(h.blend(rim, smooth), h);
        expectSensibleBlend(h.blend(glm::vec3(0.0f), smooth), h);
        expectSensibleBlend(h.blend(glm::vec3(std::numeric_limits<float>::quiet_NaN()), smooth), h);
        expectSensibleBlend(h.blend(glm::vec3(1e-30f, 0, -1e-30f), smooth), h);
    }
    // Half-way between two views of the horizon: half of each, and smoothstep keeps a tie a tie.
    const float mid = std::numbers::pi_v<float> / 16.0f;
    const ViewBlend half = h.blend({std::sin(mid), 0.0f, std::cos(mid)}, true);
    EXPECT_NEAR(half.weights[0], 0.5f, 1e-4f);
    EXPECT_NEAR(half.weights[1], 0.5f, 1e-4f);
    // Smoothstep sharpens: a 0.8 / 0.2 split moves towards the dominant view.
    const float near80 = 2.0f * mid * 0.2f;
    const ViewBlend plain = h.blend({std::sin(near80), 0.0f, std::cos(near80)}, false);
    const ViewBlend sharp = h.blend({std::sin(near80), 0.0f, std::cos(near80)}, true);
    EXPECT_GT(sharp.weights[0], plain.weights[0]);
}

TEST(ImpostorStability, DegenerateFeatureLines) {
    const ImpostorAtlas& atlas = *BakedHumanoid::get().full;
    const Image a = atlas.cell(3, 0), b = atlas.cell(3, 2);
    GpuMorpher gpu(BakedHumanoid::get().context);
    const MorphParameters m;
    // Zero-length lines at the same place in both images: no displacement, a plain cross-dissolve.
    const std::vector<FeatureLine> points = {{{10, 10}, {10, 10}}, {{40, 30}, {40, 30}}};
    const Image dissolve = morphImages(a, points, b, points, points, 0.5f, m);
    const Image noLines = morphImages(a, {}, b, {}, {}, 0.5f, m);
    EXPECT_EQ(dissolve.rgba, noLines.rgba);
    EXPECT_LE(testkit::compareImages(dissolve, gpu.morph(a, points, b, points, points, 0.5f, m), 2).fractionOverThreshold, 0.001);
    // A line collapsing to a point in the source, and a point growing to a line: finite.
    const std::vector<FeatureLine> collapsing = {{{20, 20}, {20, 20}}}, growing = {{{20, 10}, {20, 40}}};
    const Image c = morphImages(a, collapsing, b, growing, growing, 0.5f, m);
    EXPECT_GT(testkit::compareImages(c, noLines).psnr, 5.0);
    EXPECT_LE(testkit::compareImages(c, gpu.morph(a, collapsing, b, growing, growing, 0.5f, m), 2).fractionOverThreshold, 0.001);
    // Coincident lines (the same line twice) weigh twice but move pixels as one line does.
    std::vector<FeatureLine> lines0(atlas.lines(3, 0).begin(), atlas.lines(3, 0).end());
    std::vector<FeatureLine> lines2(atlas.lines(3, 2).begin(), atlas.lines(3, 2).end());
    const std::vector<FeatureLine> one0 = {lines0[4]}, one2 = {lines2[4]}, two0 = {lines0[4], lines0[4]},
                                   two2 = {lines2[4], lines2[4]};
    std::vector<FeatureLine> mid1, mid2;
    interpolateLines(one0, one2, 0.5f, mid1);
    interpolateLines(two0, two2, 0.5f, mid2);
    const Image single = morphImages(a, one0, b, one2, mid1, 0.5f, m);
    const Image doubled = morphImages(a, two0, b, two2, mid2, 0.5f, m);
    EXPECT_LE(testkit::compareImages(single, doubled, 1).fractionOverThreshold, 0.001);
    // Every bone collapsed onto one point in one image: finite, and the GPU agrees.
    std::vector<FeatureLine> collapsed(lines0.size(), FeatureLine{{32, 32}, {32, 32}});
    const Image crushed = morphImages(a, collapsed, b, lines2, lines2, 0.5f, m);
    EXPECT_LE(testkit::compareImages(crushed, gpu.morph(a, collapsed, b, lines2, lines2, 0.5f, m), 2).fractionOverThreshold, 0.001);
    // Pixels on a line (distance 0) with a = 0 stay finite.
    const MorphParameters sharp{0.0f, 2.0f, 1.0f};
    const glm::vec2 on = beierNeelySourcePosition(lines0[4].p, lines0, lines2, sharp);
    EXPECT_TRUE(std::isfinite(on.x) && std::isfinite(on.y));
    const glm::vec2 far = beierNeelySourcePosition({1e7f, -1e7f}, lines0, lines2, m);
    EXPECT_TRUE(std::isfinite(far.x) && std::isfinite(far.y));
}

TEST(ImpostorStability, MorphAtTheEndsIsTheKeyframe) {
    const ImpostorAtlas& atlas = *BakedHumanoid::get().full;
    const Image a = atlas.cell(6, 0), b = atlas.cell(6, 2);
    const auto la = atlas.lines(6, 0), lb = atlas.lines(6, 2);
    // t = 0 with the first image's own lines as targets: the first image, unchanged.
    EXPECT_EQ(morphImages(a, la, b, lb, la, 0.0f, {}).rgba, a.rgba);
    EXPECT_EQ(morphImages(a, la, b, lb, lb, 1.0f, {}).rgba, b.rgba);
}

}  // namespace
}  // namespace throng
