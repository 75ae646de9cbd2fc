// View cells as seed 003 §4.1 defines them: the eye's barycentric coordinates in the triangle of three
// baked views are clamped to that triangle (its nearest point, against sides and corners, not weight
// by weight), then optionally smoothstepped (quintic) and renormalised. The clamping is checked on
// its own (throng/render/SimplexClamp.h) and through ViewHemisphere::blend for eyes inside a cell,
// on a side, on a corner, outside every cell, at the pole and below the horizon.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "throng/render/SimplexClamp.h"
#include "throng/render/ViewHemisphere.h"

namespace throng {
namespace {

using Corners = std::array<glm::vec3, 3>;

glm::vec3 at(const Corners& c, const std::array<float, 3>& w) { return w[0] * c[0] + w[1] * c[1] + w[2] * c[2]; }

// The nearest point of the triangle to `p` by brute force: a fine grid of its barycentric coordinates.
float nearestByGrid(const Corners& c, const glm::vec3& p) {
    constexpr int kSteps = 400;
    float best = 1e30f;
    for (int i = 0; i <= kSteps; ++i)
        for (int j = 0; i + j <= kSteps; ++j) {
            const float u = float(i) / kSteps, v = float(j) / kSteps;
            best = std::min(best, glm::length(at(c, {1.0f - u - v, u, v}) - p));
        }
    return best;
}

void expectWeights(const std::array<float, 3>& got, const std::array<float, 3>& want, const char* what) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], 1e-5f) << what << ", weight " << i;
}

const Corners kRight{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)};

TEST(SimplexClamp, InsideKeepsItsOwnCoordinates) {
    expectWeights(clampedBarycentric(kRight, {0.2f, 0.3f, 0.0f}), {0.5f, 0.2f, 0.3f}, "inside");
    expectWeights(clampedBarycentric(kRight, {0.0f, 0.0f, 0.0f}), {1.0f, 0.0f, 0.0f}, "on a corner");
    expectWeights(clampedBarycentric(kRight, {0.5f, 0.5f, 0.0f}), {0.0f, 0.5f, 0.5f}, "on a side");
    // Off the plane: as its orthogonal projection.
    expectWeights(clampedBarycentric(kRight, {0.2f, 0.3f, 5.0f}), {0.5f, 0.2f, 0.3f}, "above the plane");
}

// Beyond a side or a corner, the nearest point of the triangle, which clamping each weight to [0, 1]
// and renormalising does not give: (0.5, -0.5) has coordinates (1, 0.5, -0.5); weight by weight,
// (2/3, 1/3, 0); its nearest point is (0.5, 0), (0.5, 0.5, 0).
TEST(SimplexClamp, OutsideGoesToTheNearestPointNotWeightByWeight) {
    expectWeights(clampedBarycentric(kRight, {0.5f, -0.5f, 0.0f}), {0.5f, 0.5f, 0.0f}, "beyond side ab");
    expectWeights(clampedBarycentric(kRight, {-0.5f, 0.25f, 0.0f}), {0.75f, 0.0f, 0.25f}, "beyond side ac");
    // (2, 1): coordinates (-2, 2, 1), weight by weight (0, 2/3, 1/3); its nearest point is corner b.
    expectWeights(clampedBarycentric(kRight, {2.0f, 1.0f, 0.0f}), {0.0f, 1.0f, 0.0f}, "beyond corner b");
    expectWeights(clampedBarycentric(kRight, {-1.0f, -2.0f, 0.0f}), {1.0f, 0.0f, 0.0f}, "beyond corner a");
    expectWeights(clampedBarycentric(kRight, {-0.1f, 3.0f, 0.0f}), {0.0f, 0.0f, 1.0f}, "beyond corner c");
    expectWeights(clampedBarycentric(kRight, {1.0f, 1.0f, 0.0f}), {0.0f, 0.5f, 0.5f}, "beyond side bc");
}

// Points all round three triangles (one obtuse): the clamped point is the triangle's nearest, as a
// brute-force search finds it, and the weights are >= 0 and sum to 1.
TEST(SimplexClamp, IsTheNearestPointOfTheTriangleAllRound) {
    const Corners triangles[] = {kRight,
                                 {glm::vec3(0, 0, 0), glm::vec3(4, 0, 0), glm::vec3(3.5f, 0.5f, 0)},
                                 {glm::vec3(0.2f, -0.1f, 1.0f), glm::vec3(0.3f, 0.9f, 0.8f), glm::vec3(-0.7f, 0.2f, 0.9f)}};
    std::mt19937 random(7);
    std::uniform_real_distribution<float> coordinate(-2.0f, 5.0f);
    for (const Corners& c : triangles)
        for (int k = 0; k < 60; ++k) {
            const glm::vec3 p(coordinate(random), coordinate(random), coordinate(random) * 0.3f);
            const std::array<float, 3> w = clampedBarycentric(c, p);
            EXPECT_NEAR(w[0] + w[1] + w[2], 1.0f, 1e-5f);
            for (float x : w) EXPECT_GE(x, 0.0f);
            EXPECT_LE(glm::length(at(c, w) - p), nearestByGrid(c, p) + 1e-4f) << "point " << k;
        }
}

TEST(SimplexClamp, ADegenerateTriangleGivesItsNearestSide) {
    const Corners line{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(2, 0, 0)};
    const std::array<float, 3> w = clampedBarycentric(line, {1.5f, 1.0f, 0.0f});
    EXPECT_NEAR(at(line, w).x, 1.5f, 1e-5f);
    const Corners point{glm::vec3(1, 1, 1), glm::vec3(1, 1, 1), glm::vec3(1, 1, 1)};
    const std::array<float, 3> p = clampedBarycentric(point, {0.0f, 0.0f, 0.0f});
    EXPECT_NEAR(p[0] + p[1] + p[2], 1.0f, 1e-6f);
}

// The angle between two unit vectors, accurate near 0 (acos of a dot is not).
float angleBetween(const glm::vec3& a, const glm::vec3& b) { return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)); }

// The direction a blend stands for: its views' directions weighted, normalised.
glm::vec3 blended(const ViewHemisphere& h, const ViewBlend& b) {
    glm::vec3 sum(0.0f);
    for (int i = 0; i < 3; ++i) sum += b.weights[i] * h.direction(b.views[i]);
    return glm::normalize(sum);
}

// The least angle, over every triangle of every cell, between `eye` and the triangle's nearest point
// to the eye's ray (brute force over the whole grid).
float leastAngleOverAllCells(const ViewHemisphere& h, const glm::vec3& eye) {
    float best = 10.0f;
    for (int e = 0; e + 1 < h.elevations(); ++e)
        for (int a = 0; a < h.azimuths(); ++a) {
            const int a1 = (a + 1) % h.azimuths();
            const auto v = [&](int x, int y) { return h.direction(std::uint32_t(y * h.azimuths() + x)); };
            for (const Corners& c : {Corners{v(a, e), v(a1, e), v(a1, e + 1)}, Corners{v(a, e), v(a, e + 1), v(a1, e + 1)}}) {
                const glm::vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
                const float across = glm::dot(n, eye), offset = glm::dot(n, c[0]);
                const glm::vec3 onPlane = across * offset > 1e-9f ? eye * (offset / across) : eye;
                best = std::min(best, angleBetween(glm::normalize(at(c, clampedBarycentric(c, onPlane))), eye));
            }
        }
    return best;
}

float weightOf(const ViewBlend& b, std::uint32_t view) {
    float w = 0.0f;
    for (int i = 0; i < 3; ++i)
        if (b.views[i] == view) w += b.weights[i];
    return w;
}

glm::vec3 fromAngles(float azimuth, float elevation) {
    return {std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth)};
}

TEST(ViewCells, AnEyeInsideACellIsItsOwnBlendOfTheThreeViews) {
    const ViewHemisphere h;  // 16 x 4
    std::mt19937 random(11);
    std::uniform_real_distribution<float> azimuth(0.0f, 2.0f * std::numbers::pi_v<float>), elevation(0.02f, 1.15f);
    for (int k = 0; k < 200; ++k) {
        const glm::vec3 eye = fromAngles(azimuth(random), elevation(random));
        const ViewBlend b = h.blend(eye);
        // Inside the hemisphere's cells the blend points exactly at the eye (no extrapolation).
        EXPECT_GT(glm::dot(blended(h, b), eye), 1.0f - 1e-5f) << "eye " << k;
        EXPECT_NEAR(leastAngleOverAllCells(h, eye), 0.0f, 1e-4f);
    }
}

TEST(ViewCells, OnASideTwoViewsOnACornerOne) {
    const ViewHemisphere h;
    // On the meridian between views (0, ring 1) and (0, ring 2): only those two.
    const float e1 = h.elevation(1), e2 = h.elevation(2);
    const ViewBlend side = h.blend(fromAngles(0.0f, 0.3f * e1 + 0.7f * e2));
    const std::uint32_t lower = std::uint32_t(1 * h.azimuths()), upper = std::uint32_t(2 * h.azimuths());
    EXPECT_NEAR(weightOf(side, lower) + weightOf(side, upper), 1.0f, 1e-5f);
    EXPECT_GT(weightOf(side, lower), 0.2f);
    EXPECT_GT(weightOf(side, upper), 0.5f);
    // On the great circle between two views of one ring: only those two, half each half-way.
    const glm::vec3 a = h.direction(lower), b = h.direction(lower + 1);
    const ViewBlend ring = h.blend(glm::normalize(a + b));
    EXPECT_NEAR(weightOf(ring, lower), 0.5f, 1e-4f);
    EXPECT_NEAR(weightOf(ring, lower + 1), 0.5f, 1e-4f);
    // On a corner: that view alone.
    for (std::uint32_t v = 0; v < h.viewCount(); ++v) EXPECT_NEAR(weightOf(h.blend(h.direction(v)), v), 1.0f, 1e-4f) << "view " << v;
}

// Outside every cell (above the top ring, at the pole, below the horizon): the blend is the nearest
// point of the nearest cell, on its side or corner, never an extrapolation, and the same as a brute
// force over every cell finds.
TEST(ViewCells, OutsideEveryCellTheNearestCellsNearestPoint) {
    const ViewHemisphere h;
    const int top = h.elevations() - 1;
    const std::vector<glm::vec3> outside = {glm::vec3(0, 1, 0), fromAngles(0.3f, 1.4f), fromAngles(2.0f, 1.3f), fromAngles(0.1f, -0.4f),
                                            glm::vec3(0.3f, -0.9f, 0.2f), fromAngles(4.0f, -1.2f), glm::vec3(0, -1, 0)};
    for (const glm::vec3& eye : outside) {
        const ViewBlend b = h.blend(eye);
        float sum = 0.0f;
        for (int i = 0; i < 3; ++i) {
            EXPECT_GE(b.weights[i], 0.0f);
            sum += b.weights[i];
            if (b.weights[i] > 0.0f) {
                const int ring = int(b.views[i]) / h.azimuths();
                EXPECT_TRUE(eye.y > 0.0f ? ring == top : ring == 0) << "eye (" << eye.x << ", " << eye.y << ", " << eye.z << ")";
            }
        }
        EXPECT_NEAR(sum, 1.0f, 1e-5f);
        const float angle = angleBetween(blended(h, b), eye);
        EXPECT_NEAR(angle, leastAngleOverAllCells(h, eye), 1e-4f) << "eye (" << eye.x << ", " << eye.y << ", " << eye.z << ")";
    }
}

// Moving the eye in small steps up a meridian from below the horizon, through every ring, to near the
// pole, and round the hemisphere between two rings: the weights never jump (a cell changes where the
// two cells agree). (At the pole itself every side of the top ring is equally near: crossing it, the
// nearest side changes, as it must.)
TEST(ViewCells, WeightsChangeContinuouslyAcrossCells) {
    const ViewHemisphere h;
    const auto weightsOf = [&](const ViewBlend& b) {
        std::vector<float> w(h.viewCount(), 0.0f);
        for (int i = 0; i < 3; ++i) w[b.views[i]] += b.weights[i];
        return w;
    };
    for (bool smooth : {false, true}) {
        std::vector<float> last = weightsOf(h.blend(fromAngles(0.37f, -0.5f), smooth));
        for (int k = 1; k <= 4000; ++k) {
            const float t = float(k) / 4000.0f;
            const glm::vec3 eye = k <= 2000 ? fromAngles(0.37f, -0.5f + t * 2.0f * 2.0f) : fromAngles(0.37f + (t - 0.5f) * 4.0f * std::numbers::pi_v<float>, 0.9f);
            const std::vector<float> now = weightsOf(h.blend(eye, smooth));
            float jump = 0.0f;
            for (std::size_t v = 0; v < now.size(); ++v) jump = std::max(jump, std::abs(now[v] - last[v]));
            if (k != 2001) {
                EXPECT_LT(jump, 0.02f) << "step " << k << (smooth ? " (smoothstep)" : "");
            }
            last = now;
        }
    }
}

// The smoothstep modulates the clamped weights, then renormalises (seed 003 §4.1.2).
TEST(ViewCells, SmoothstepModulatesTheClampedWeightsThenRenormalises) {
    const ViewHemisphere h;
    const auto quintic = [](float x) { return x * x * x * (x * (x * 6.0f - 15.0f) + 10.0f); };
    for (const glm::vec3& eye : {fromAngles(0.2f, 0.5f), fromAngles(3.0f, 0.1f), glm::vec3(0, 1, 0), fromAngles(1.0f, -0.3f)}) {
        const ViewBlend plain = h.blend(eye), smooth = h.blend(eye, true);
        float sum = 0.0f;
        for (int i = 0; i < 3; ++i) sum += quintic(plain.weights[i]);
        for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(smooth.views[i], plain.views[i]);
            EXPECT_NEAR(smooth.weights[i], quintic(plain.weights[i]) / sum, 1e-5f);
        }
    }
}

}  // namespace
}  // namespace throng
