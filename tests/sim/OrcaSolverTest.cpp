// ORCA's half-planes and linear programs (sim/OrcaSolver.h) on their own: small crowds stepped with
// the solver alone (no navigation mesh) must never interpenetrate and must get where they go.
//
//   * A preferred velocity that breaks no line is returned as it is; one above the speed limit is
//     cut to it, in its direction.
//   * Two walkers head-on, four crossing at right angles, and eight swapping places across a circle
//     keep their bodies apart (within 1 cm: the time step's rounding) and all reach their goals.
//   * Two bodies that start overlapping are pushed apart within a few steps.
//   * A walker hemmed in by more neighbours than it can avoid still gets a finite velocity within
//     its limit (the infeasible case, solved by the 3-D program).

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "throng/sim/OrcaSolver.h"

namespace throng::sim {
namespace {

using orca::Body;
using orca::Line;

constexpr float kRadius = 0.3f, kSpeed = 1.3f, kHorizon = 2.0f, kDt = 0.05f;

struct Walker {
    Body body;
    glm::vec2 goal;
};

// Steps `walkers` toward their goals for `seconds`, every one avoiding every other; returns the
// smallest distance between two bodies' surfaces seen (negative: they overlapped). Preferred
// velocities are turned by up to a degree each way, differently for each walker and step: exactly
// symmetric encounters (head-on on one line) otherwise stall, each walker only slowing for the other,
// and ORCA's users break that symmetry so.
float stepCrowd(std::vector<Walker>& walkers, float seconds) {
    std::vector<Line> lines, scratch(walkers.size());
    std::vector<glm::vec2> next(walkers.size());
    float closest = 1e9f;
    for (float t = 0.0f; t < seconds; t += kDt) {
        for (std::size_t i = 0; i < walkers.size(); ++i) {
            lines.clear();
            for (std::size_t j = 0; j < walkers.size(); ++j)
                if (j != i) lines.push_back(orca::agentLine(walkers[i].body, walkers[j].body, kHorizon, kDt));
            const glm::vec2 to = walkers[i].goal - walkers[i].body.position;
            const float d = glm::length(to);
            glm::vec2 preferred = d > kSpeed * kDt ? to / d * kSpeed : to / kDt;
            const float turn = 0.017f * std::sin(float(i) * 12.9898f + t * 78.233f);
            preferred = glm::vec2(preferred.x * std::cos(turn) - preferred.y * std::sin(turn),
                                  preferred.x * std::sin(turn) + preferred.y * std::cos(turn));
            next[i] = orca::solve(lines, 0, preferred, kSpeed, scratch);
        }
        for (std::size_t i = 0; i < walkers.size(); ++i) {
            walkers[i].body.velocity = next[i];
            walkers[i].body.position += next[i] * kDt;
        }
        for (std::size_t i = 0; i < walkers.size(); ++i)
            for (std::size_t j = i + 1; j < walkers.size(); ++j)
                closest = std::min(closest, glm::length(walkers[i].body.position - walkers[j].body.position) - 2.0f * kRadius);
    }
    return closest;
}

Walker walker(glm::vec2 from, glm::vec2 to) { return {{from, glm::vec2(0.0f), kRadius}, to}; }

void expectAllArrived(const std::vector<Walker>& walkers) {
    for (std::size_t i = 0; i < walkers.size(); ++i)
        EXPECT_LT(glm::length(walkers[i].goal - walkers[i].body.position), 0.1f) << "walker " << i << " did not arrive";
}

TEST(OrcaSolver, KeepsAVelocityThatBreaksNoLine) {
    std::vector<Line> scratch(1);
    const Line l{glm::vec2(0.0f, -1.0f), glm::vec2(1.0f, 0.0f)};  // allowed: above y = -1 (left of +x)
    const glm::vec2 v = orca::solve(std::span(&l, 1), 0, glm::vec2(0.5f, 0.2f), kSpeed, scratch);
    EXPECT_FLOAT_EQ(v.x, 0.5f);
    EXPECT_FLOAT_EQ(v.y, 0.2f);
}

TEST(OrcaSolver, CutsAPreferredSpeedToTheLimit) {
    std::vector<Line> scratch;
    const glm::vec2 v = orca::solve({}, 0, glm::vec2(3.0f, 4.0f), 1.0f, scratch);
    EXPECT_NEAR(glm::length(v), 1.0f, 1e-6f);
    EXPECT_NEAR(v.x / v.y, 0.75f, 1e-6f);
}

TEST(OrcaSolver, MovesOntoAViolatedLine) {
    std::vector<Line> scratch(1);
    const Line l{glm::vec2(0.0f, 0.5f), glm::vec2(1.0f, 0.0f)};  // allowed: y >= 0.5
    const glm::vec2 v = orca::solve(std::span(&l, 1), 0, glm::vec2(0.3f, 0.0f), kSpeed, scratch);
    EXPECT_NEAR(v.x, 0.3f, 1e-6f);
    EXPECT_NEAR(v.y, 0.5f, 1e-6f);
}

// Two walkers abreast converging: the one that takes all of the change (share 1, the other having the
// right of way and keeping its velocity) clears the other within the horizon on its own; taking half
// (share 0.5, ORCA's reciprocal rule) it would clear it only if the other did its half too.
TEST(OrcaSolver, AWalkerTakingAllTheChangeClearsTheOtherAlone) {
    const float horizon = 2.0f, dt = 1.0f / 60.0f;
    const orca::Body self{glm::vec2(0.0f, 0.0f), glm::vec2(1.0f, 0.3f), kRadius};
    const orca::Body other{glm::vec2(0.0f, 0.8f), glm::vec2(1.0f, -0.3f), kRadius};
    // The closest the two bodies' centres come within the horizon, self at `v`, the other as it goes.
    const auto closest = [&](glm::vec2 v) {
        float best = 1e9f;
        for (float t = 0.0f; t <= horizon; t += 0.01f)
            best = std::min(best, glm::length(other.position + other.velocity * t - (self.position + v * t)));
        return best;
    };
    ASSERT_LT(closest(self.velocity), 2.0f * kRadius);  // as they go, they collide
    std::vector<Line> scratch(1);
    for (float share : {0.5f, 1.0f}) {
        const Line l = orca::agentLine(self, other, horizon, dt, share);
        const glm::vec2 v = orca::solve(std::span(&l, 1), 0, self.velocity, kSpeed, scratch);
        if (share == 1.0f) EXPECT_GE(closest(v), 2.0f * kRadius - 1e-3f) << "taking all of the change";
        else EXPECT_LT(closest(v), 2.0f * kRadius - 0.01f) << "taking half, it relies on the other";
    }
}

TEST(OrcaSolver, TwoWalkersHeadOnPassWithoutTouching) {
    std::vector<Walker> w{walker({0.0f, 0.0f}, {8.0f, 0.0f}), walker({8.0f, 0.0f}, {0.0f, 0.0f})};
    const float closest = stepCrowd(w, 12.0f);
    EXPECT_GT(closest, -0.01f);
    expectAllArrived(w);
}

TEST(OrcaSolver, FourWalkersCrossingAtRightAnglesKeepApart) {
    std::vector<Walker> w{walker({-5.0f, 0.0f}, {5.0f, 0.0f}), walker({5.0f, 0.1f}, {-5.0f, 0.1f}),
                          walker({0.05f, -5.0f}, {0.05f, 5.0f}), walker({-0.1f, 5.0f}, {-0.1f, -5.0f})};
    const float closest = stepCrowd(w, 20.0f);
    EXPECT_GT(closest, -0.01f);
    expectAllArrived(w);
}

TEST(OrcaSolver, EightWalkersSwapPlacesAcrossACircle) {
    std::vector<Walker> w;
    for (int k = 0; k < 8; ++k) {
        const float a = float(k) * 0.785398f;
        const glm::vec2 p(4.0f * std::cos(a), 4.0f * std::sin(a));
        w.push_back(walker(p, -p));
    }
    const float closest = stepCrowd(w, 30.0f);
    EXPECT_GT(closest, -0.01f);
    expectAllArrived(w);
}

TEST(OrcaSolver, PushesOverlappingBodiesApart) {
    std::vector<Walker> w{walker({0.0f, 0.0f}, {0.0f, 0.0f}), walker({0.3f, 0.0f}, {0.3f, 0.0f})};  // 0.3 m into each other
    stepCrowd(w, 1.0f);
    EXPECT_GT(glm::length(w[0].body.position - w[1].body.position), 2.0f * kRadius - 0.01f);
}

TEST(OrcaSolver, AHemmedInWalkerGetsAFiniteVelocityWithinItsLimit) {
    // Twelve neighbours closing in from every side, all at once: no velocity avoids them all.
    const Body self{glm::vec2(0.0f), glm::vec2(0.0f), kRadius};
    std::vector<Line> lines, scratch(12);
    for (int k = 0; k < 12; ++k) {
        const float a = float(k) * 0.523599f;
        const glm::vec2 dir(std::cos(a), std::sin(a));
        lines.push_back(orca::agentLine(self, {dir * 0.7f, -dir * kSpeed, kRadius}, kHorizon, kDt));
    }
    const glm::vec2 v = orca::solve(lines, 0, glm::vec2(kSpeed, 0.0f), kSpeed, scratch);
    EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y));
    EXPECT_LE(glm::length(v), kSpeed + 1e-4f);
}

}  // namespace
// A wall along z = 0 from x = -5 to 5, its free side z > 0 (Detour's winding runs it towards -x).
TEST(OrcaSolver, AWallLimitsOnlyTheVelocityTowardsIt) {
    const orca::Body walker{{0.0f, 0.5f}, {0.0f, 0.0f}, 0.1f};
    orca::Line wall;
    ASSERT_TRUE(orca::wallLine(walker, {5.0f, 0.0f}, {-5.0f, 0.0f}, 0.5f, 0.1f, wall));
    std::vector<orca::Line> scratch(1);
    const std::vector<orca::Line> lines{wall};
    // Straight at the wall: slowed to the gap (0.4 m) over the horizon; along it: untouched.
    const glm::vec2 into = orca::solve(lines, 1, {0.0f, -2.0f}, 2.0f, scratch);
    EXPECT_NEAR(into.y, -0.8f, 1e-4f);
    const glm::vec2 along = orca::solve(lines, 1, {1.5f, 0.0f}, 2.0f, scratch);
    EXPECT_NEAR(along.x, 1.5f, 1e-5f);
    EXPECT_NEAR(along.y, 0.0f, 1e-5f);
    // Away from it: free.
    EXPECT_NEAR(orca::solve(lines, 1, {0.0f, 1.0f}, 2.0f, scratch).y, 1.0f, 1e-5f);
}

TEST(OrcaSolver, AWallFacesOnlyWalkersBesideItOnItsFreeSide) {
    orca::Line wall;
    // Beyond its ends: the next segment's business (a joint in a straight wall is no post).
    EXPECT_FALSE(orca::wallLine({{6.0f, 0.3f}, {}, 0.1f}, {5.0f, 0.0f}, {-5.0f, 0.0f}, 0.5f, 0.1f, wall));
    // Behind it (the far side of the wall).
    EXPECT_FALSE(orca::wallLine({{0.0f, -0.5f}, {}, 0.1f}, {5.0f, 0.0f}, {-5.0f, 0.0f}, 0.5f, 0.1f, wall));
    // A walker reaching into it is sent out within one step.
    const orca::Body touching{{0.0f, 0.05f}, {0.0f, 0.0f}, 0.1f};
    ASSERT_TRUE(orca::wallLine(touching, {5.0f, 0.0f}, {-5.0f, 0.0f}, 0.5f, 0.1f, wall));
    std::vector<orca::Line> scratch(1);
    EXPECT_NEAR(orca::solve(std::vector<orca::Line>{wall}, 1, {0.0f, 0.0f}, 2.0f, scratch).y, 0.5f, 1e-4f);
    // Further into it than it can leave in one step: out of it as fast as it may walk, not standing
    // still (a hard line that no velocity within the limit meets is relaxed, not given up).
    EXPECT_NEAR(orca::solve(std::vector<orca::Line>{wall}, 1, {0.0f, 0.0f}, 0.3f, scratch).y, 0.3f, 1e-4f);
    // A degenerate segment is no wall.
    EXPECT_FALSE(orca::wallLine(touching, {1.0f, 0.0f}, {1.0f, 0.0f}, 0.5f, 0.1f, wall));
}

}  // namespace throng::sim
