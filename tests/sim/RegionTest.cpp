// Regions stepped apart: which region owns a point, agents near a border seen by the neighbouring
// region as ghosts (so that avoidance works across it), agents handed over when they cross it
// (walking on, same slot, no jump), and the same trajectories with 1, 2 or 4 threads.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <set>

#include "PlazaWalkers.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/CounterRng.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/NavMesh.h"
#include "throng/sim/SceneError.h"
#include "throng/sim/SimulationClock.h"
#include "throng/sim/TownRegions.h"

using namespace throng;
using namespace throng::sim;

namespace {

constexpr float kRadius = 0.35f;

// A corridor 40 m along x and 6 m wide; with `split`, two regions meeting at x = 0.
std::shared_ptr<const NavMesh> corridor() {
    NavGeometry g;
    g.addBox(glm::vec3(-20, -0.5f, -3), glm::vec3(20, 0, 3), true);
    return NavMesh::build(g);
}
RegionGrid halves() { return RegionGrid(glm::dvec2(-20.0, -3.0), 10.0, 4, 1, {0, 0, 1, 1}); }

struct Run {
    std::shared_ptr<Locomotion> walk;
    Crowd crowd;
};

std::unique_ptr<Run> walkers(const std::shared_ptr<const NavMesh>& nav, bool avoidance, const RegionGrid& regions,
                             Locomotion::AvoidanceModel model,
                             const std::vector<std::pair<glm::vec3, glm::vec3>>& legs) {
    auto run = std::make_unique<Run>();
    Locomotion::Settings s;
    s.avoidance = avoidance;
    s.avoidanceModel = model;
    s.radius = kRadius;
    s.regions = regions;
    run->walk = std::make_shared<Locomotion>(nav, s);
    static const auto humanoid = makeSeedHumanoid();
    for (const auto& [from, to] : legs) {
        Locomotion::Actor a;
        a.tmpl = humanoid;
        a.walkClip = humanoid->findClip("walk");
        a.start = from;
        a.goal = to;
        a.speed = 1.3;
        a.stream = run->crowd.size();
        run->crowd.add(humanoid, run->walk, run->walk->addActor(a));
    }
    return run;
}

glm::vec3 at(Locomotion& walk, std::uint32_t slot) { return glm::vec3(walk.referencePoint(slot, FrameContext{}, nullptr)[3]); }

}  // namespace

TEST(Regions, EveryPointBelongsToTheRegionOfItsCell) {
    // 5 x 3 cells of 10 m from (-25, -15), regions of 2 x 2 cells: 3 across, 2 deep.
    const RegionGrid grid = RegionGrid::tiled(glm::dvec2(-25.0, -15.0), 10.0, 5, 3, 2, 2);
    EXPECT_EQ(grid.regionCount(), 6u);
    EXPECT_EQ(grid.regionOf(-24.0, -14.0), 0u);
    EXPECT_EQ(grid.regionOf(-6.0, -14.0), 0u);
    EXPECT_EQ(grid.regionOf(-4.0, -14.0), 1u);
    EXPECT_EQ(grid.regionOf(24.0, -14.0), 2u) << "the last column is a region of one cell";
    EXPECT_EQ(grid.regionOf(0.0, 6.0), 4u);
    EXPECT_EQ(grid.regionOf(-1000.0, 1000.0), 3u) << "outside the grid: the nearest cell's region";
    std::uint32_t near[8];
    EXPECT_EQ(grid.regionsNear(-10.0, -10.0, 2.0, 0, near), 0) << "inside its region, away from borders";
    ASSERT_EQ(grid.regionsNear(-5.5, 4.5, 1.0, 0, near), 3) << "at a corner: the three others";
    EXPECT_EQ(near[0], 1u);
    EXPECT_EQ(near[1], 3u);
    EXPECT_EQ(near[2], 4u);
    EXPECT_THROW(RegionGrid(glm::dvec2(0.0), 10.0, 2, 1, {0, 2}), std::invalid_argument) << "region 1 owns nothing";
    EXPECT_THROW(RegionGrid(glm::dvec2(0.0), 10.0, 2, 2, {0, 0}), std::invalid_argument) << "too few cells";
}

TEST(Regions, TownRegionsAreRectanglesOfBlocksCoveringTheTown) {
    TownDescription town;  // 5 x 5 blocks of 4 tiles of 8 m, and a last road: 168 m square
    town.regionBlocks = {2, 3};
    const RegionGrid grid = townRegions(town, "scene.json");
    EXPECT_EQ(grid.regionCount(), 6u);
    EXPECT_DOUBLE_EQ(grid.cellSize(), 32.0);
    EXPECT_EQ(grid.regionOf(-84.0 + 1.0, -84.0 + 1.0), 0u);
    EXPECT_EQ(grid.regionOf(-84.0 + 65.0, -84.0 + 1.0), 1u);
    EXPECT_EQ(grid.regionOf(83.0, 83.0), 5u) << "the last road belongs to the last block's region";
    town.regions = {{{0, 0}, {5, 2}}, {{0, 2}, {5, 4}}};
    try {
        townRegions(town, "scene.json");
        FAIL() << "a row of blocks in no region was accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.path(), "/town/regions");
        EXPECT_NE(e.reason().find("block (0, 4)"), std::string::npos) << e.what();
    }
}

// Each region test runs for both avoidance models.
class RegionModels : public ::testing::TestWithParam<Locomotion::AvoidanceModel> {};

TEST_P(RegionModels, AnAgentAvoidsAGhostComingTheOtherWayAcrossABorder) {
    // Walkers from both ends in the same three lanes meet at the border x = 0. In separate crowds
    // they would pass through each other; as ghosts of each other they steer round.
    const Locomotion::AvoidanceModel model = GetParam();
    const auto nav = corridor();
    std::vector<std::pair<glm::vec3, glm::vec3>> legs;
    for (float side : {-1.0f, 1.0f})
        for (float z : {-1.5f, 0.0f, 1.5f}) legs.push_back({glm::vec3(18.0f * side, 0, z), glm::vec3(-18.0f * side, 0, z)});
    struct Outcome {
        double contact = 0.0, overlap = 0.0;  // pair-seconds within 5 cm of touching, and interpenetrating by more
        float progress = 0.0f;
        std::size_t ghosts = 0, handovers = 0;
    };
    auto cross = [&](bool avoidance, const RegionGrid& regions) {
        auto run = walkers(nav, avoidance, regions, model, legs);
        SimulationClock clock;
        Outcome o;
        for (int f = 0; f < 40 * 60; ++f, clock.advance()) {
            run->crowd.step(clock.context());
            o.ghosts += run->walk->lastGhostCount();
            o.handovers += run->walk->lastHandoverCount();
            if (f < 2) continue;
            for (std::uint32_t i = 0; i < legs.size(); ++i)
                for (std::uint32_t j = i + 1; j < legs.size(); ++j) {
                    const glm::vec3 d = at(*run->walk, i) - at(*run->walk, j);
                    const float apart = std::sqrt(d.x * d.x + d.z * d.z);
                    if (apart < 2 * kRadius + 0.05f) o.contact += clock.step();
                    if (apart < 2 * kRadius - 0.05f) o.overlap += clock.step();
                }
        }
        for (std::uint32_t i = 0; i < legs.size(); ++i)
            o.progress += (glm::length(legs[i].second - legs[i].first) - glm::length(legs[i].second - at(*run->walk, i))) / float(legs.size());
        return o;
    };
    const Outcome split = cross(true, halves()), whole = cross(true, RegionGrid()), blind = cross(false, halves());
    EXPECT_GT(split.ghosts, 0u);
    EXPECT_GE(split.handovers, legs.size()) << "each walker crossed the border";
    EXPECT_EQ(whole.ghosts + whole.handovers, 0u) << "one region: nothing to exchange";
    // Without avoidance DetourCrowd still pushes bodies apart after each move (they brush past each
    // other), ORCA's walkers walk through each other; with it, ORCA's pass within a few cm.
    if (model == Locomotion::AvoidanceModel::Detour)
        EXPECT_GT(blind.contact, 4.0 * split.contact + 1.0) << "avoidance across the border keeps them apart";
    else
        EXPECT_GT(blind.overlap, 4.0 * split.overlap + 1.0) << "avoidance across the border keeps them apart";
    EXPECT_LT(split.contact, whole.contact + 2.0) << "about as well as one crowd does";
    EXPECT_GT(split.progress, 30.0f) << "and they still get there";
}

TEST_P(RegionModels, AnAgentCrossingABorderIsHandedOverAndWalksOnWithoutAJump) {
    const auto nav = corridor();
    const std::vector<std::pair<glm::vec3, glm::vec3>> legs = {{glm::vec3(-15, 0, 0.5f), glm::vec3(15, 0, 0.5f)}};
    auto split = walkers(nav, true, halves(), GetParam(), legs), whole = walkers(nav, true, RegionGrid(), GetParam(), legs);
    SimulationClock clock;
    glm::vec3 last = at(*split->walk, 0);
    float worstStep = 0.0f, worstApart = 0.0f;
    int handedAt = -1;
    for (int f = 0; f < 30 * 60; ++f, clock.advance()) {
        split->crowd.step(clock.context());
        whole->crowd.step(clock.context());
        const glm::vec3 p = at(*split->walk, 0);
        if (f > 0) worstStep = std::max(worstStep, glm::length(p - last));
        last = p;
        worstApart = std::max(worstApart, glm::length(p - at(*whole->walk, 0)));
        if (split->walk->lastHandoverCount() > 0) {
            EXPECT_EQ(handedAt, -1) << "handed over once";
            handedAt = f;
            EXPECT_EQ(split->walk->region(0), 1u);
            EXPECT_GT(p.x, 0.0f);
        }
        if (handedAt >= 0 && f == handedAt + 30) {
            EXPECT_GT(split->walk->speed(0), 1.0) << "still walking after the handover";
        }
    }
    EXPECT_GT(handedAt, 0);
    EXPECT_LT(worstStep, 1.3f / 60.0f * 1.5f) << "no jump at the handover";
    EXPECT_LT(worstApart, 0.2f) << "the same walk as in one crowd";
    EXPECT_NEAR(last.x, 15.0f, 0.6f) << "it arrived";
}

TEST_P(RegionModels, RegionsStepBitwiseIdenticallyWithOneTwoOrFourThreads) {
    // A plaza of 60 m in 3 x 3 regions, 400 walkers with avoidance crossing it.
    const std::shared_ptr<const NavMesh> nav = test::plaza(true);
    auto trajectory = [&](unsigned threads, std::size_t* handovers) {
        Locomotion::Settings s;
        s.avoidance = true;
        s.avoidanceModel = GetParam();
        s.regions = RegionGrid::tiled(glm::dvec2(-30.0), 20.0, 3, 3, 1, 1);
        auto walk = test::plazaWalkers(nav, s, 400, 5, true);
        ThreadTeam team(threads);
        SimulationClock clock;
        std::vector<float> out;
        *handovers = 0;
        team.run([&] {
            for (int f = 0; f < 300; ++f, clock.advance()) {
                walk->advance(clock.context());
                *handovers += walk->lastHandoverCount();
            }
        });
        for (std::uint32_t i = 0; i < walk->size(); ++i) {
            const Mat4 m = walk->referencePoint(i, clock.context(), nullptr);
            for (int k = 0; k < 16; ++k) out.push_back(float(m[k / 4][k % 4]));
            out.push_back(float(walk->clipTime(i, 0.0)));
        }
        return out;
    };
    std::size_t handovers = 0, other = 0;
    const std::vector<float> one = trajectory(1, &handovers);
    EXPECT_GT(handovers, 50u) << "the walkers should cross borders, or the comparison proves little";
    for (unsigned threads : {2u, 4u}) {
        const std::vector<float> many = trajectory(threads, &other);
        ASSERT_EQ(many.size(), one.size());
        EXPECT_EQ(std::memcmp(many.data(), one.data(), one.size() * sizeof(float)), 0) << threads << " threads";
        EXPECT_EQ(other, handovers);
    }
}

TEST_P(RegionModels, ARegionThatFillsMakesRoomForItsArrivals) {
    // 240 walkers start in the left half and walk into the right one, which starts empty: its crowd
    // has room for its share and a quarter more at first (DetourCrowd's is allocated up front: 214
    // agents), so it grows as they arrive, and every one is handed over and walks on.
    const auto nav = corridor();
    std::vector<std::pair<glm::vec3, glm::vec3>> legs;
    for (int i = 0; i < 240; ++i) {
        const float x = -19.5f + float(i % 24) * 0.8f, z = -2.7f + float(i / 24) * 0.6f;
        legs.push_back({glm::vec3(x, 0, z), glm::vec3(x + 20.5f, 0, z)});
    }
    auto run = walkers(nav, false, halves(), GetParam(), legs);
    SimulationClock clock;
    std::size_t handovers = 0, bytesBefore = 0;
    for (int f = 0; f < 30 * 60; ++f, clock.advance()) {
        ASSERT_NO_THROW(run->crowd.step(clock.context())) << "frame " << f;
        if (f == 0) bytesBefore = run->walk->stepBytes();
        handovers += run->walk->lastHandoverCount();
    }
    EXPECT_EQ(handovers, legs.size()) << "every walker crossed into the right half once";
    for (std::uint32_t i = 0; i < legs.size(); ++i) {
        EXPECT_EQ(run->walk->region(i), 1u) << "walker " << i;
        EXPECT_NEAR(at(*run->walk, i).x, legs[i].second.x, 1.5f) << "walker " << i << " arrived";
    }
    EXPECT_GT(run->walk->stepBytes(), bytesBefore + 200000) << "the right half's crowd grew: " << bytesBefore << " to " << run->walk->stepBytes() << " bytes";
}

INSTANTIATE_TEST_SUITE_P(Models, RegionModels,
                         ::testing::Values(Locomotion::AvoidanceModel::Detour, Locomotion::AvoidanceModel::Orca),
                         [](const ::testing::TestParamInfo<Locomotion::AvoidanceModel>& model) {
                             return model.param == Locomotion::AvoidanceModel::Orca ? std::string("orca") : std::string("detour");
                         });

TEST(Navigation, ATiledMeshIsJoinedAcrossItsTiles) {
    // The corridor in tiles of 8 m (five along it): a walker crosses them all to the far end, and
    // random points fall on every tile, never off the corridor.
    NavGeometry g;
    g.addBox(glm::vec3(-20, -0.5f, -3), glm::vec3(20, 0, 3), true);
    g.addBox(glm::vec3(-2, 0, -3), glm::vec3(2, 4, 0), false);  // a block across half of it
    NavMeshSettings tiled;
    tiled.tileSize = 8.0f;
    const std::shared_ptr<const NavMesh> nav = NavMesh::build(g, tiled);
    std::set<int> tilesHit;
    const CounterRng rng(2, 9);
    for (std::uint64_t k = 0; k < 400; ++k) {
        const glm::vec3 p = nav->randomPoint(rng, k);
        EXPECT_LE(std::abs(p.z), 3.0f);
        EXPECT_FALSE(std::abs(p.x) < 2.0f && p.z < 0.0f) << "inside the block";
        tilesHit.insert(int(std::floor((p.x + 20.0f) / 8.0f)));
    }
    EXPECT_GE(tilesHit.size(), 5u);
    auto run = walkers(nav, false, halves(), Locomotion::AvoidanceModel::Detour, {{glm::vec3(-18, 0, -2), glm::vec3(18, 0, -2)}});
    SimulationClock clock;
    for (int f = 0; f < 40 * 60; ++f, clock.advance()) run->crowd.step(clock.context());
    EXPECT_NEAR(at(*run->walk, 0).x, 18.0f, 0.6f) << "it walked round the block through every tile";
}

TEST(Locomotion, DestinationsLieWithinTheRangeAskedFor) {
    // A plaza of 60 m: with a range of 8 m, every new destination is within 8 m each way of where
    // the walker stood (give or take the snap to the mesh); without one, they spread over it all.
    const std::shared_ptr<const NavMesh> nav = test::plaza(false);
    for (double range : {8.0, 0.0}) {
        Locomotion::Settings s;
        s.destinationRange = range;
        auto walk = test::plazaWalkers(nav, s, 30, 8, false);
        SimulationClock clock;
        std::vector<glm::vec3> before(walk->size()), last(walk->size());
        float farthest = 0.0f;
        int drawn = 0;
        for (int f = 0; f < 60 * 60; ++f, clock.advance()) {
            for (std::uint32_t i = 0; i < walk->size(); ++i) before[i] = at(*walk, i);
            walk->advance(clock.context());
            for (std::uint32_t i = 0; i < walk->size(); ++i) {
                if (f > 0 && walk->destination(i) == last[i]) continue;
                last[i] = walk->destination(i);
                const glm::vec3 d = walk->destination(i) - (f > 0 ? before[i] : at(*walk, i));
                farthest = std::max({farthest, std::abs(d.x), std::abs(d.z)});
                ++drawn;
            }
        }
        EXPECT_GT(drawn, 60) << "walkers reached destinations and drew new ones";
        if (range > 0.0) {
            EXPECT_LE(farthest, float(range) + 0.5f);
        } else {
            EXPECT_GT(farthest, 30.0f);
        }
    }
}

TEST(Regions, FarRegionsStepInTurnAndTheirWalkersKeepTheirPace) {
    // The plaza in 3 x 3 regions seen from one corner: regions beyond 15 m step every fourth step.
    const std::shared_ptr<const NavMesh> nav = test::plaza(false);
    auto run = [&](int every, unsigned threads, std::size_t* deferred) {
        Locomotion::Settings s;
        s.regions = RegionGrid::tiled(glm::dvec2(-30.0), 20.0, 3, 3, 1, 1);
        s.farDistance = 15.0, s.farEvery = every;
        auto walk = test::plazaWalkers(nav, s, 300, 5, false);
        walk->setViewpoint(glm::vec3(-30.0f, 2.0f, -30.0f));
        ThreadTeam team(threads);
        SimulationClock clock;
        std::vector<float> travelled(walk->size(), 0.0f), out;
        *deferred = 0;
        team.run([&] {
            for (int f = 0; f < 120; ++f, clock.advance()) {
                std::vector<glm::vec3> before(walk->size());
                for (std::uint32_t i = 0; i < walk->size(); ++i) before[i] = walk->position(i);
                walk->advance(clock.context());
                *deferred += walk->lastDeferredCount();
                for (std::uint32_t i = 0; i < walk->size(); ++i) travelled[i] += glm::distance(before[i], walk->position(i));
            }
        });
        for (std::uint32_t i = 0; i < walk->size(); ++i) out.push_back(walk->position(i).x), out.push_back(walk->position(i).z);
        out.insert(out.end(), travelled.begin(), travelled.end());
        return out;
    };
    std::size_t deferred = 0, other = 0;
    const std::vector<float> every = run(1, 1, &deferred);
    EXPECT_EQ(deferred, 0u) << "without the approximation every region steps";
    const std::vector<float> far = run(4, 1, &deferred);
    // Eight regions of nine are far; three steps in four they wait: most walkers are deferred most steps.
    EXPECT_GT(deferred, 300u * 120u / 3u);
    EXPECT_LT(deferred, 300u * 120u * 3u / 4u);
    // Deferred walkers carry on at their last velocity: the distance walked stays within 5 %.
    double walkedEvery = 0, walkedFar = 0;
    for (std::size_t i = 600; i < every.size(); ++i) walkedEvery += every[i], walkedFar += far[i];
    EXPECT_NEAR(walkedFar / walkedEvery, 1.0, 0.05) << walkedFar << " m against " << walkedEvery << " m";
    // Which regions wait is decided by the step count and the viewpoint only: threads change nothing.
    EXPECT_EQ(run(4, 2, &other), far);
    EXPECT_EQ(other, deferred);
}
