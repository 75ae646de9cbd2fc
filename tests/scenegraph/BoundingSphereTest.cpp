// BoundingSphere: construction checks, expansion by points and spheres (including the degenerate
// cases), transformation by rotation, non-uniform scale and shear.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "throng/scenegraph/BoundingSphere.h"

using namespace throng;

namespace {

// Points on the surface of `s` in many directions (pulled in by 1e-12 so that rounding in the
// sample itself cannot put it outside `s`): a merged sphere must contain them all.
std::vector<Vec3> surfaceSamples(const BoundingSphere& s, std::mt19937_64& rng, int n = 64) {
    std::normal_distribution<double> g;
    std::vector<Vec3> pts{s.center()};
    for (int i = 0; i < n; ++i) {
        Vec3 d(g(rng), g(rng), g(rng));
        const double len = glm::length(d);
        if (len < 1e-9) continue;
        pts.push_back(s.center() + d * (s.radius() * (1.0 - 1e-12) / len));
    }
    for (int a = 0; a < 3; ++a)
        for (double sign : {-1.0, 1.0}) {
            Vec3 d(0.0);
            d[a] = sign * s.radius() * (1.0 - 1e-12);
            pts.push_back(s.center() + d);
        }
    return pts;
}

}  // namespace

TEST(BoundingSphere, DefaultIsEmptyAndMergesAsNothing) {
    BoundingSphere empty;
    EXPECT_FALSE(empty.valid());
    EXPECT_FALSE(empty.contains(Vec3(0.0)));
    BoundingSphere s(Vec3(1, 2, 3), 4);
    s.expandBy(empty);
    EXPECT_EQ(s, BoundingSphere(Vec3(1, 2, 3), 4));
    empty.expandBy(s);
    EXPECT_EQ(empty, s);
    EXPECT_FALSE(BoundingSphere().transformed(Mat4(2.0)).valid());
}

TEST(BoundingSphere, RejectsNonFiniteAndNegativeArgumentsNamingThem) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    try {
        BoundingSphere(Vec3(0, nan, 0), 1);
        FAIL() << "NaN centre accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'center'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("y"), std::string::npos) << e.what();
    }
    try {
        BoundingSphere(Vec3(0.0), inf);
        FAIL() << "infinite radius accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'radius'"), std::string::npos) << e.what();
    }
    EXPECT_THROW(BoundingSphere(Vec3(0.0), -1.0), std::invalid_argument);
    BoundingSphere s(Vec3(0.0), 1.0);
    try {
        s.expandBy(Vec3(inf, 0, 0));
        FAIL() << "infinite point accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'point'"), std::string::npos) << e.what();
    }
    EXPECT_EQ(s, BoundingSphere(Vec3(0.0), 1.0)) << "a rejected call must leave the sphere unchanged";
    EXPECT_THROW(s.inflate(nan), std::invalid_argument);
    EXPECT_THROW(s.inflate(-0.5), std::invalid_argument);
}

TEST(BoundingSphere, ExpandByPoints) {
    BoundingSphere s;
    s.expandBy(Vec3(1, 0, 0));
    EXPECT_TRUE(s.valid());
    EXPECT_EQ(s.radius(), 0.0);
    s.expandBy(Vec3(-1, 0, 0));
    EXPECT_NEAR(s.radius(), 1.0, 1e-12);
    EXPECT_NEAR(glm::length(s.center()), 0.0, 1e-12);
    const BoundingSphere before = s;
    s.expandBy(Vec3(0, 0.5, 0));  // inside: nothing changes
    EXPECT_EQ(s, before);
}

TEST(BoundingSphere, MergeOneInsideTheOther) {
    const BoundingSphere big(Vec3(0.0), 10.0), small(Vec3(2, 1, 0), 3.0);
    BoundingSphere a = big;
    a.expandBy(small);
    EXPECT_EQ(a, big);
    BoundingSphere b = small;
    b.expandBy(big);
    EXPECT_EQ(b, big);
}

TEST(BoundingSphere, MergeCoincidentCentres) {
    BoundingSphere a(Vec3(5, 5, 5), 2.0);
    a.expandBy(BoundingSphere(Vec3(5, 5, 5), 3.0));
    EXPECT_EQ(a, BoundingSphere(Vec3(5, 5, 5), 3.0));
    BoundingSphere same(Vec3(1, 1, 1), 1.0);
    same.expandBy(BoundingSphere(Vec3(1, 1, 1), 1.0));
    EXPECT_EQ(same, BoundingSphere(Vec3(1, 1, 1), 1.0));
}

TEST(BoundingSphere, MergeZeroRadii) {
    BoundingSphere a(Vec3(0.0), 0.0);
    a.expandBy(BoundingSphere(Vec3(0.0), 0.0));
    EXPECT_EQ(a.radius(), 0.0);
    a.expandBy(BoundingSphere(Vec3(4, 0, 0), 0.0));
    EXPECT_NEAR(a.radius(), 2.0, 1e-12);
    EXPECT_NEAR(a.center().x, 2.0, 1e-12);
}

TEST(BoundingSphere, MergeIsMinimalForTwoSpheresAndAlwaysContainsBoth) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> pos(-100, 100), rad(0, 30);
    for (int i = 0; i < 2000; ++i) {
        const BoundingSphere a(Vec3(pos(rng), pos(rng), pos(rng)), rad(rng));
        const BoundingSphere b(Vec3(pos(rng), pos(rng), pos(rng)), rad(rng));
        BoundingSphere m = a;
        m.expandBy(b);
        ASSERT_TRUE(m.contains(a)) << i;
        ASSERT_TRUE(m.contains(b)) << i;
        for (const Vec3& p : surfaceSamples(a, rng, 8)) ASSERT_TRUE(m.contains(p));
        for (const Vec3& p : surfaceSamples(b, rng, 8)) ASSERT_TRUE(m.contains(p));
        // The smallest sphere holding two spheres has radius (d + r1 + r2) / 2 unless one holds the other.
        const double d = glm::length(a.center() - b.center());
        const double expected = std::max({a.radius(), b.radius(), 0.5 * (d + a.radius() + b.radius())});
        ASSERT_NEAR(m.radius(), expected, 1e-9 * (1 + expected));
    }
}

// clearlyContains is a shortcut for expandBy: wherever it says yes, expandBy changes no bit. Spheres
// are drawn right at the edge of containment (and far from the origin), where rounding decides.
TEST(BoundingSphere, ClearlyContainsOnlyWhereExpandByChangesNothing) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1, 1), share(0, 1);
    int yes = 0, no = 0;
    for (int i = 0; i < 20000; ++i) {
        const double scale = std::pow(10.0, 6.0 * share(rng) - 1.0);  // 0.1 m to 100 km
        const Vec3 offset = Vec3(unit(rng), unit(rng), unit(rng)) * (1e6 * share(rng));
        const BoundingSphere bound(offset, scale);
        const double r = scale * (i % 2 ? 0.5 : share(rng));
        const Vec3 dir = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)) + Vec3(1e-9));
        const double room = (scale - r) * (1.0 + 1e-6 * unit(rng));  // at the edge, either side
        const BoundingSphere inner(offset + dir * std::max(room, 0.0), r);
        BoundingSphere grown = bound;
        grown.expandBy(inner);
        if (bound.clearlyContains(inner)) {
            ++yes;
            ASSERT_EQ(grown, bound) << i;
        } else {
            ++no;
        }
    }
    EXPECT_GT(yes, 1000);  // the shortcut is taken, and it is not always taken
    EXPECT_GT(no, 1000);
    EXPECT_FALSE(BoundingSphere().clearlyContains(BoundingSphere(Vec3(0), 1)));
    EXPECT_FALSE(BoundingSphere(Vec3(0), 1).clearlyContains(BoundingSphere()));
    EXPECT_FALSE(BoundingSphere(Vec3(0), 1).clearlyContains(BoundingSphere(Vec3(0), 0.6)));  // radius over half
}

TEST(BoundingSphere, TransformRotationKeepsRadius) {
    const BoundingSphere s(Vec3(1, 2, 3), 2.0);
    Mat4 t = glm::mat4_cast(glm::angleAxis(0.7, glm::normalize(Vec3(1, 2, 3))));
    t[3] = Vec4(10, 0, -5, 1);
    const BoundingSphere r = s.transformed(t);
    EXPECT_NEAR(r.radius(), 2.0, 1e-12);
    const Vec3 expectedCentre = Vec3(t * Vec4(1, 2, 3, 1));
    EXPECT_NEAR(glm::length(r.center() - expectedCentre), 0.0, 1e-12);
}

TEST(BoundingSphere, TransformNonUniformScaleUsesLargestAxis) {
    const BoundingSphere s(Vec3(0.0), 1.0);
    Mat4 m = glm::mat4_cast(glm::angleAxis(1.1, glm::normalize(Vec3(0, 1, 1))));
    m[0] *= 2.0;  // scale x by 2, y by 0.5, z by 3 (in the rotated frame)
    m[1] *= 0.5;
    m[2] *= 3.0;
    const BoundingSphere r = s.transformed(m);
    EXPECT_NEAR(r.radius(), 3.0, 1e-12) << "exact for rotation and scale";
}

TEST(BoundingSphere, TransformWithShearStaysConservative) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 500; ++i) {
        Mat4 m(1.0);
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) m[c][r] = u(rng) * 2;
        m[3] = Vec4(u(rng) * 50, u(rng) * 50, u(rng) * 50, 1);
        const BoundingSphere s(Vec3(u(rng), u(rng), u(rng)) * 10.0, std::abs(u(rng)) * 5);
        const BoundingSphere t = s.transformed(m);
        for (const Vec3& p : surfaceSamples(s, rng, 32))
            ASSERT_TRUE(t.contains(Vec3(m * Vec4(p, 1.0)))) << "case " << i;
    }
}

TEST(BoundingSphere, MaxScaleFactorIsExactForOrthogonalColumns) {
    Mat4 m(1.0);
    m[0] = Vec4(0, 4, 0, 0);
    m[1] = Vec4(-2, 0, 0, 0);
    m[2] = Vec4(0, 0, 1, 0);
    EXPECT_DOUBLE_EQ(maxScaleFactor(m), 4.0);
    // Shear [[1,1],[0,1]] has spectral norm (1+sqrt5)/2 = 1.618; the bound must not be below it.
    Mat4 shear(1.0);
    shear[1][0] = 1.0;
    EXPECT_GE(maxScaleFactor(shear), (1.0 + std::sqrt(5.0)) / 2.0);
}
