// The counting type itself: each operation counted by the cost model's rules, through glm too, so
// that the kernel checks rest on a counter that is right.

#include <gtest/gtest.h>

#include <algorithm>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "KernelCheck.h"

using namespace throng;
using namespace throng::counting;

namespace {
OpTally ops(std::uint64_t m, std::uint64_t a, std::uint64_t d = 0, std::uint64_t s = 0) {
    OpTally t;
    t.mults = m, t.adds = a, t.divs = d, t.sqrts = s;
    return t;
}
}  // namespace

TEST(CountedScalar, CountsEachOperationByTheCostModelsRules) {
    const CDouble a = 3.0, b = 4.0;
    EXPECT_EQ(executedBy([&] { (void)(a + b - a); }), ops(0, 2));
    EXPECT_EQ(executedBy([&] { (void)(a * b / a); }), ops(1, 0, 1));
    EXPECT_EQ(executedBy([&] { (void)(0.5 * a); }), ops(1, 0)) << "a multiply by a literal is executed";
    EXPECT_EQ(executedBy([&] { (void)(a < b), (void)(a == b), (void)(a >= b); }), ops(0, 3)) << "comparisons are additions";
    EXPECT_EQ(executedBy([&] { (void)std::max(a, b), (void)std::min({a, b, a}); }), ops(0, 3));
    EXPECT_EQ(executedBy([&] { (void)detail::sqrtOf(a), (void)detail::sinOf(a), (void)detail::acosOf(CDouble(0.5)); }),
              ops(0, 0, 0, 3))
        << "sqrt, and transcendental functions priced as sqrt";
    EXPECT_EQ(executedBy([&] { (void)detail::fmodOf(a, b); }), ops(0, 0, 1)) << "fmod is a division";
    EXPECT_EQ(executedBy([&] { (void)(-a), (void)detail::absOf(-b), (void)CFloat(a), (void)detail::isFiniteOf(a); }),
              ops(0, 0))
        << "negation, abs, conversions and isfinite are free";
    CDouble c = a;
    EXPECT_EQ(executedBy([&] { c += b, c *= b, c -= a, c /= b; }), ops(1, 2, 1));
    EXPECT_DOUBLE_EQ(c.value(), ((3.0 + 4.0) * 4.0 - 3.0) / 4.0);
}

TEST(CountedScalar, CountsThroughGlm) {
    using V3 = glm::vec<3, CDouble>;
    using M4 = glm::mat<4, 4, CDouble>;
    using M3 = glm::mat<3, 3, CFloat>;
    using Q = glm::qua<CFloat>;
    const V3 u(1.0, 2.0, 3.0), v(4.0, 5.0, 6.0);
    EXPECT_EQ(executedBy([&] { (void)glm::dot(u, v); }), ops(3, 2));
    EXPECT_EQ(executedBy([&] { (void)glm::length(u); }), ops(3, 2, 0, 1));
    EXPECT_EQ(executedBy([&] { (void)(u * CDouble(2.0) + v); }), ops(3, 3));
    const M4 m(2.0);
    EXPECT_EQ(executedBy([&] { (void)(m * m); }), ops(64, 48));
    const M3 r(1.0f);
    EXPECT_EQ(executedBy([&] { (void)(r * r); }), ops(27, 18));
    EXPECT_EQ(executedBy([&] { (void)(r * glm::vec<3, CFloat>(1.0f)); }), ops(9, 6));
    const Q q(1.0f, 0.0f, 0.0f, 0.0f);
    EXPECT_EQ(executedBy([&] { (void)(q * q); }), ops(16, 12));
    EXPECT_EQ(executedBy([&] { (void)glm::dot(q, q); }), ops(4, 3));
    EXPECT_EQ(executedBy([&] { (void)(-q); }), ops(0, 0));
    // Results are those of the built-in type.
    EXPECT_EQ(glm::length(u).value(), glm::length(glm::dvec3(1.0, 2.0, 3.0)));
}
