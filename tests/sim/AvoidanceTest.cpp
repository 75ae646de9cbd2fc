// Local avoidance proven by trajectories, not by a counter: two groups walk towards each other
// along a corridor. With avoidance (DetourCrowd's velocity sampling and separation) they steer
// round each other and reach the far end; without it they walk into each other and stay pressed
// together. DetourCrowd pushes overlapping agents apart after every move, avoidance or not, so
// centres never end a step much closer than the sum of the radii either way: what avoidance
// changes is how long people spend in contact, and whether they get where they are going.

#include <gtest/gtest.h>

#include <limits>

#include "throng/actors/Crowd.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/NavMesh.h"
#include "throng/sim/SimulationClock.h"

using namespace throng;
using namespace throng::sim;

namespace {

constexpr float kRadius = 0.35f;      // Locomotion's default agent radius
constexpr float kTolerance = 0.05f;   // metres: closer than 2 radii + this is contact

// A corridor 40 m long and 6 m wide.
std::shared_ptr<const NavMesh> corridor() {
    NavGeometry g;
    g.addBox(glm::vec3(-20, -0.5f, -3), glm::vec3(20, 0, 3), true);
    return NavMesh::build(g);
}

struct Crossing {
    float closest = std::numeric_limits<float>::infinity();  // closest approach of two agents, centre to centre
    double contact = 0.0;                                    // seconds pairs of agents spent in contact
    float progress = 0.0f;                                   // mean distance walked towards the goal
};

// Three walkers from each end of the corridor, each to the far end of its own lane, for 40 s:
// lanes 1.5 m apart, so each walker meets another head on.
Crossing cross(const std::shared_ptr<const NavMesh>& nav, bool avoidance, int quality = 3, float range = 12.0f,
               std::vector<glm::vec3>* end = nullptr) {
    Locomotion::Settings settings;
    settings.avoidance = avoidance;
    settings.avoidanceQuality = quality;
    settings.neighbourRange = range;
    settings.radius = kRadius;
    auto walk = std::make_shared<Locomotion>(nav, settings);
    Crowd crowd;
    static const auto humanoid = makeSeedHumanoid();
    std::vector<glm::vec3> starts, goals;
    for (int side : {-1, 1})
        for (int lane = 0; lane < 3; ++lane) {
            const float z = -1.5f + 1.5f * float(lane);
            Locomotion::Actor a;
            a.tmpl = humanoid;
            a.walkClip = humanoid->findClip("walk");
            a.start = glm::vec3(18.0f * float(side), 0.0f, z);
            a.goal = glm::vec3(-18.0f * float(side), 0.0f, z);
            a.speed = 1.3;
            a.stream = starts.size();
            starts.push_back(a.start);
            goals.push_back(*a.goal);
            crowd.add(humanoid, walk, walk->addActor(a));
        }
    SimulationClock clock;
    Crossing result;
    std::vector<glm::vec3> at(starts.size());
    for (int f = 0; f < 40 * 60; ++f, clock.advance()) {
        crowd.step(clock.context());
        for (std::uint32_t i = 0; i < at.size(); ++i) at[i] = glm::vec3(walk->referencePoint(i, clock.context(), nullptr)[3]);
        if (f < 2) continue;  // the first step places them on the mesh
        for (std::size_t i = 0; i < at.size(); ++i)
            for (std::size_t j = i + 1; j < at.size(); ++j) {
                const glm::vec3 d = at[i] - at[j];
                const float distance = std::sqrt(d.x * d.x + d.z * d.z);
                result.closest = std::min(result.closest, distance);
                if (distance < 2 * kRadius + kTolerance) result.contact += clock.step();
            }
    }
    for (std::size_t i = 0; i < at.size(); ++i)
        result.progress += (glm::length(goals[i] - starts[i]) - glm::length(goals[i] - at[i])) / float(at.size());
    if (end) *end = at;
    return result;
}

}  // namespace

TEST(Avoidance, WalkersCrossingInACorridorPassEachOtherOnlyWithAvoidance) {
    const auto nav = corridor();
    const Crossing with = cross(nav, true), without = cross(nav, false);
    RecordProperty("contactSecondsWithAvoidance", std::to_string(with.contact));
    RecordProperty("contactSecondsWithoutAvoidance", std::to_string(without.contact));
    // Overlaps are resolved after each move either way: nobody ends a step inside anybody.
    EXPECT_GE(with.closest, 2 * kRadius - kTolerance);
    EXPECT_GE(without.closest, 2 * kRadius - kTolerance);
    // Without avoidance the walkers meeting head on stay pressed together; with it they pass.
    EXPECT_GT(without.contact, 10.0) << "pair-seconds in contact without avoidance";
    EXPECT_LT(with.contact, 0.1 * without.contact) << "pair-seconds in contact with avoidance";
    EXPECT_GT(with.progress, 34.0f) << "with avoidance everyone reaches the far end (36 m)";
    EXPECT_LT(without.progress, 0.75f * with.progress) << "without it the head-on pairs block each other";
}

TEST(Avoidance, AGoalOffTheMeshIsRefused) {
    const auto nav = corridor();
    auto walk = std::make_shared<Locomotion>(nav, Locomotion::Settings{});
    static const auto humanoid = makeSeedHumanoid();
    Locomotion::Actor a;
    a.tmpl = humanoid;
    a.start = glm::vec3(0.0f);
    a.goal = glm::vec3(0.0f, 0.0f, 60.0f);
    try {
        walk->addActor(a);
        FAIL() << "a goal 58 m off the corridor was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("goal"), std::string::npos) << e.what();
    }
}

// Avoidance quality is a knob that acts: the coarsest sampling and the shortest neighbour range
// still let the walkers pass each other, on other paths than the finest setting takes.
TEST(Avoidance, CoarserQualityStillPassesOnOtherPaths) {
    const auto nav = corridor();
    std::vector<glm::vec3> fineEnd, coarseEnd;
    const Crossing fine = cross(nav, true, 3, 12.0f, &fineEnd);
    const Crossing coarse = cross(nav, true, 0, 6.0f, &coarseEnd);
    const Crossing without = cross(nav, false);
    EXPECT_LT(coarse.contact, 0.25 * without.contact) << "pair-seconds in contact, coarse avoidance";
    EXPECT_GT(coarse.progress, 30.0f);
    EXPECT_NE(fineEnd, coarseEnd) << "the quality setting changed nothing";
    EXPECT_EQ(fineEnd.size(), coarseEnd.size());
    std::vector<glm::vec3> again;
    cross(nav, true, 3, 12.0f, &again);
    EXPECT_EQ(fineEnd, again);
    (void)fine;
}

TEST(Avoidance, QualityAndRangeOutOfRangeAreRefused) {
    const auto nav = corridor();
    Locomotion::Settings s;
    s.avoidanceQuality = 4;
    EXPECT_THROW(Locomotion(nav, s), std::invalid_argument);
    s.avoidanceQuality = -1;
    EXPECT_THROW(Locomotion(nav, s), std::invalid_argument);
    s.avoidanceQuality = 0;
    s.neighbourRange = 0.5f;
    EXPECT_THROW(Locomotion(nav, s), std::invalid_argument);
    s.neighbourRange = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(Locomotion(nav, s), std::invalid_argument);
    s.neighbourRange = 6.0f;
    EXPECT_NO_THROW(Locomotion(nav, s));
}
