// Key-framing tables: step, linear and cubic-spline sampling against hand-computed values,
// orientations along the shortest arc, clip ends, looping, and holding keys for far actors.

#include <gtest/gtest.h>

#include <cmath>

#include "throng/actors/ActorTemplate.h"

using namespace throng;

namespace {

// One node with a rotation DOF and an orientation DOF.
std::shared_ptr<const ActorTemplate> oneJoint(std::vector<ClipChannel> channels) {
    ActorTemplateBuilder b("joint");
    SkeletonNode n;
    n.name = "j";
    n.dofs = {Dof::rotation(glm::vec3(1, 0, 0), -10.0f, 10.0f), Dof{DofKind::Orientation, {}, 0, 0, {0, 0, 0, 1}}};
    b.addNode(n);
    b.addClip(std::make_shared<AnimationClip>("c", std::move(channels)));
    return b.build();
}

ClipChannel scalar(Interpolation i, std::vector<float> times, std::vector<float> values) {
    ClipChannel c;
    c.node = 0;
    c.dof = 0;
    c.interpolation = i;
    c.times = std::move(times);
    c.values = std::move(values);
    return c;
}

float sampleAngle(const ActorTemplate& t, double time, bool loop = false, bool hold = false) {
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    t.clips()[0]->sample(t, time, loop, {}, dofs, nullptr, hold);
    return dofs[0];
}

glm::quat sampleOrientation(const ActorTemplate& t, double time) {
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    t.clips()[0]->sample(t, time, false, {}, dofs);
    return glm::quat(dofs[4], dofs[1], dofs[2], dofs[3]);
}

}  // namespace

TEST(Clips, StepHoldsThePreviousKey) {
    const auto t = oneJoint({scalar(Interpolation::Step, {0, 1, 2}, {1, 5, -3})});
    EXPECT_EQ(sampleAngle(*t, 0.0), 1.0f);
    EXPECT_EQ(sampleAngle(*t, 0.999), 1.0f);
    EXPECT_EQ(sampleAngle(*t, 1.0), 5.0f);
    EXPECT_EQ(sampleAngle(*t, 1.5), 5.0f);
    EXPECT_EQ(sampleAngle(*t, 2.0), -3.0f);
}

TEST(Clips, LinearInterpolatesAndClampsAtTheEnds) {
    const auto t = oneJoint({scalar(Interpolation::Linear, {0.5f, 1.5f, 2.5f}, {0, 2, 1})});
    EXPECT_FLOAT_EQ(sampleAngle(*t, 0.0), 0.0f) << "before the first key: the first value";
    EXPECT_FLOAT_EQ(sampleAngle(*t, 1.0), 1.0f);
    EXPECT_FLOAT_EQ(sampleAngle(*t, 2.0), 1.5f);
    EXPECT_FLOAT_EQ(sampleAngle(*t, 2.5), 1.0f) << "the clip's end";
    EXPECT_FLOAT_EQ(sampleAngle(*t, 9.0), 1.0f) << "after the end, clamped";
    EXPECT_FLOAT_EQ(sampleAngle(*t, 2.0, false, true), 2.0f) << "holding keys: the previous key";
}

TEST(Clips, CubicSplineMatchesTheHermiteFormula) {
    // Keys (0, p0=1, m0=2) and (2, p1=3, m1=-1): at u = 0.25, t = 0.5, with tangents times dt = 2.
    ClipChannel c = scalar(Interpolation::CubicSpline, {0, 2}, {/*in*/ 0, /*value*/ 1, /*out*/ 2, /*in*/ -1, /*value*/ 3, /*out*/ 0});
    const auto t = oneJoint({c});
    const float u = 0.25f, dt = 2.0f;
    const float h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u, h01 = -2 * u * u * u + 3 * u * u,
                h11 = u * u * u - u * u;
    EXPECT_NEAR(sampleAngle(*t, 0.5), h00 * 1 + h10 * dt * 2 + h01 * 3 + h11 * dt * -1, 1e-6);
    EXPECT_FLOAT_EQ(sampleAngle(*t, 0.0), 1.0f);
    EXPECT_FLOAT_EQ(sampleAngle(*t, 2.0), 3.0f);
}

TEST(Clips, OrientationsTakeTheShortestArcAtQAndMinusQ) {
    // Key 1 is the same rotation as key 0's 170 degrees turn... written as -q: the short way round.
    const glm::quat a = glm::angleAxis(0.0f, glm::vec3(0, 1, 0));
    const glm::quat b = -glm::angleAxis(0.4f, glm::vec3(0, 1, 0));  // 0.4 rad, stored negated
    ClipChannel c;
    c.node = 0;
    c.dof = 1;
    c.times = {0, 1};
    c.values = {a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w};
    const auto t = oneJoint({c});
    const glm::quat mid = sampleOrientation(*t, 0.5);
    EXPECT_NEAR(glm::angle(mid), 0.2f, 1e-5) << "half of 0.4 rad, not half of the long way";
    EXPECT_NEAR(glm::length(mid), 1.0f, 1e-6);
    // Nearly equal keys: no division by sin(theta) ~ 0, still unit length.
    const glm::quat n = glm::angleAxis(1e-7f, glm::vec3(1, 0, 0));
    ClipChannel same = c;
    same.values = {a.x, a.y, a.z, a.w, n.x, n.y, n.z, n.w};
    const glm::quat q = sampleOrientation(*oneJoint({same}), 0.5);
    EXPECT_TRUE(std::isfinite(q.w));
    EXPECT_NEAR(glm::length(q), 1.0f, 1e-6);
}

TEST(Clips, LoopingWrapsTime) {
    const auto t = oneJoint({scalar(Interpolation::Linear, {0, 1, 2}, {0, 4, 0})});
    EXPECT_FLOAT_EQ(sampleAngle(*t, 2.5, true), 2.0f);
    EXPECT_FLOAT_EQ(sampleAngle(*t, -0.5, true), 2.0f) << "negative times wrap too";
    EXPECT_DOUBLE_EQ(t->clips()[0]->localTime(7.0, true), 1.0);
    EXPECT_DOUBLE_EQ(t->clips()[0]->localTime(7.0, false), 2.0);
}

TEST(Clips, InactiveNodesAreNeverSampled) {
    const auto t = oneJoint({scalar(Interpolation::Linear, {0, 1}, {0, 1})});
    std::vector<float> dofs(t->dofValueCount(), -99.0f);
    const std::vector<std::uint8_t> inactive = {0};
    EXPECT_EQ(t->clips()[0]->sample(*t, 0.5, false, inactive, dofs), 0u);
    EXPECT_EQ(dofs[0], -99.0f);
}
