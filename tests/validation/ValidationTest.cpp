// Do the walkers move like people? Scenarios of the RiMEA guideline (version 3) for the
// verification of pedestrian simulations, each a small scene file in tests/validation/scenes, run
// through the Simulation as throng-town runs it, each asserting the guideline's acceptance:
//
//   * RiMEA 1: one walker at 1.33 m/s along a 2 m x 40 m corridor arrives in 26 to 34 s. The same
//     walker made 30 % faster must fail the same check (the test can fail).
//   * RiMEA 6: 20 walkers turn a 90 degree corner (corridors 2 m wide): every one arrives round it
//     within 60 s, no body crosses a wall, and the share of agent-seconds with bodies
//     interpenetrating by more than 5 cm stays under 2 %.
//   * RiMEA 7: four populations of 50 walkers each with the guideline's free speeds (after Weidmann
//     1993), walking without interaction: every walker's measured speed lies in its population's
//     range, and each population's speeds follow the distribution drawn from (Kolmogorov-Smirnov,
//     1 % level).
//
// Each prints what it measured (the figures the results page reports).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "throng/sim/Locomotion.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/sim/SpeedProfile.h"

namespace throng {
namespace {

const std::string kScenes = THRONG_VALIDATION_SCENES;
constexpr double kBodyRadius = 0.35;  // Locomotion's agent radius, metres

// A scenario's world and its walkers, group by group.
class Scenario {
public:
    explicit Scenario(const std::string& file, const std::function<void(sim::SceneDescription&)>& edit = {}) {
        sim::SceneDescription scene = sim::parseSceneFile(kScenes + "/" + file);
        if (edit) edit(scene);
        floors_ = scene.walkways->floors;
        world_ = sim::Simulation::build(std::move(scene));
        for (const auto& g : world_->groups()) {
            std::vector<std::uint32_t> slots;
            for (ActorId id : g.actors) slots.push_back(world_->crowd().state().slot[id]);
            slots_.push_back(std::move(slots));
        }
    }
    void step() { world_->step(); }
    double time() const { return world_->now().time; }
    double stepSeconds() const { return world_->description().step; }
    const std::vector<std::uint32_t>& group(std::size_t g) const { return slots_.at(g); }
    glm::vec3 position(std::uint32_t slot) const { return world_->locomotion()->position(slot); }
    // Whether a body of radius `radius` centred at `p` lies on the floors (its disc inside their
    // union, checked at its centre and eight points of its rim).
    bool bodyOnFloors(glm::vec3 p, double radius) const {
        for (int k = -1; k < 8; ++k) {
            const double a = k * 0.25 * 3.14159265358979;
            const double x = p.x + (k < 0 ? 0.0 : radius * std::cos(a)), z = p.z + (k < 0 ? 0.0 : radius * std::sin(a));
            const bool inside = std::any_of(floors_.begin(), floors_.end(), [&](const sim::AreaDescription& f) {
                return std::abs(x - f.center.x) <= 0.5 * f.size.x + 1e-6 && std::abs(z - f.center.y) <= 0.5 * f.size.y + 1e-6;
            });
            if (!inside) return false;
        }
        return true;
    }

private:
    std::vector<sim::AreaDescription> floors_;
    std::unique_ptr<sim::Simulation> world_;
    std::vector<std::vector<std::uint32_t>> slots_;
};

// Bodies interpenetrating: each step, every counted walker whose disc overlaps another's by more
// than `depth` adds the step's time to the overlapping agent-seconds.
struct OverlapMeter {
    double depth = 0.05;
    double agentSeconds = 0.0, overlappingSeconds = 0.0, deepest = 0.0;

    void add(const std::vector<glm::vec3>& bodies, double dt) {
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            double worst = 0.0;
            for (std::size_t j = 0; j < bodies.size(); ++j) {
                if (i == j) continue;
                const double dx = bodies[i].x - bodies[j].x, dz = bodies[i].z - bodies[j].z;
                worst = std::max(worst, 2.0 * kBodyRadius - std::sqrt(dx * dx + dz * dz));
            }
            agentSeconds += dt;
            if (worst > depth) overlappingSeconds += dt;
            deepest = std::max(deepest, worst);
        }
    }
    double share() const { return agentSeconds > 0.0 ? overlappingSeconds / agentSeconds : 0.0; }
};

// RiMEA 1: the time the walker takes from its start to the line 1.5 m before the corridor's end
// (where it starts slowing for its goal), scaled to the corridor's 40 m; nullopt if it never gets there.
std::optional<double> rimea1Time(Scenario& s) {
    const std::uint32_t walker = s.group(0).at(0);
    const double startX = s.position(walker).x, line = 38.5;
    double lastX = startX, lastT = 0.0;
    while (s.time() < 60.0) {
        s.step();
        const double x = s.position(walker).x, t = s.time();
        if (x >= line) {
            const double crossed = lastT + (t - lastT) * (line - lastX) / (x - lastX);
            return crossed * 40.0 / (line - startX);  // the guideline's 40 m at the speed measured
        }
        lastX = x, lastT = t;
    }
    return std::nullopt;
}

TEST(Validation, Rimea1KeepsSpeedInCorridor) {
    Scenario s("rimea1-corridor.json");
    const auto t = rimea1Time(s);
    ASSERT_TRUE(t) << "the walker never reached the corridor's end";
    std::printf("RiMEA 1: 40 m in %.2f s (accepted: 26 to 34 s; 1.33 m/s gives 30.1 s)\n", *t);
    RecordProperty("rimea1_seconds", std::to_string(*t));
    EXPECT_GE(*t, 26.0);
    EXPECT_LE(*t, 34.0);
}

TEST(Validation, Rimea1FailsForAWalker30PercentFaster) {
    Scenario s("rimea1-corridor.json", [](sim::SceneDescription& d) { d.actors[0].speed = glm::dvec2(1.33 * 1.3); });
    const auto t = rimea1Time(s);
    ASSERT_TRUE(t);
    std::printf("RiMEA 1 at 1.73 m/s: 40 m in %.2f s, outside 26 to 34 s as it must be\n", *t);
    EXPECT_LT(*t, 26.0) << "a walker 30 % faster than the guideline's passed its check: the check cannot fail";
}

TEST(Validation, Rimea6TurnsTheCorner) {
    Scenario s("rimea6-corner.json");
    const auto& walkers = s.group(0);
    ASSERT_EQ(walkers.size(), 20u);
    const double arrival = 8.0;  // z of the line 6 m round the corner
    std::vector<double> arrived(walkers.size(), -1.0);
    OverlapMeter overlaps;
    std::size_t offFloor = 0;
    while (s.time() < 60.0 && std::count(arrived.begin(), arrived.end(), -1.0) > 0) {
        s.step();
        std::vector<glm::vec3> turning;  // walkers not yet round the corner
        for (std::size_t i = 0; i < walkers.size(); ++i) {
            const glm::vec3 p = s.position(walkers[i]);
            if (!s.bodyOnFloors(p, kBodyRadius - 0.05)) ++offFloor;
            if (arrived[i] < 0.0 && p.z >= arrival) arrived[i] = s.time();
            if (arrived[i] < 0.0) turning.push_back(p);
        }
        overlaps.add(turning, s.stepSeconds());
    }
    const auto missing = std::count(arrived.begin(), arrived.end(), -1.0);
    const double last = *std::max_element(arrived.begin(), arrived.end());
    std::printf("RiMEA 6: %zu of 20 round the corner, the last after %.1f s; bodies off the floor (5 cm allowed) in %zu "
                "walker-steps; overlapping by more than 5 cm: %.3f %% of %.0f agent-seconds, deepest %.3f m\n",
                walkers.size() - std::size_t(missing), last, offFloor, 100.0 * overlaps.share(), overlaps.agentSeconds,
                overlaps.deepest);
    RecordProperty("rimea6_overlap_share", std::to_string(overlaps.share()));
    EXPECT_EQ(missing, 0) << "walkers still before the corner after 60 s";
    EXPECT_EQ(offFloor, 0u) << "a body crossed a wall";
    EXPECT_LT(overlaps.share(), 0.02);
}

TEST(Validation, Rimea7SpeedsFollowThePopulations) {
    Scenario s("rimea7-demography.json");
    const double from = 5.0, to = 45.0;  // measured between these lines (x), after speeding up
    struct Walk {
        std::optional<glm::vec3> atFrom;
        double tFrom = 0.0;
        std::optional<double> speed;
    };
    std::vector<std::vector<Walk>> walks(4);
    std::vector<std::vector<glm::vec3>> last(4);
    for (std::size_t g = 0; g < 4; ++g) {
        walks[g].resize(s.group(g).size());
        for (std::uint32_t slot : s.group(g)) last[g].push_back(s.position(slot));
    }
    double lastT = 0.0;
    while (s.time() < 150.0) {
        s.step();
        const double t = s.time();
        bool done = true;
        for (std::size_t g = 0; g < 4; ++g)
            for (std::size_t i = 0; i < walks[g].size(); ++i) {
                const glm::vec3 p = s.position(s.group(g)[i]), q = last[g][i];
                Walk& w = walks[g][i];
                const auto crossing = [&](double line) {  // where and when it crossed x = line this step
                    const double f = (line - q.x) / (p.x - q.x);
                    return std::pair(q + float(f) * (p - q), lastT + f * (t - lastT));
                };
                if (!w.atFrom && q.x < from && p.x >= from) std::tie(w.atFrom, w.tFrom) = crossing(from);
                if (w.atFrom && !w.speed && q.x < to && p.x >= to) {
                    const auto [at, when] = crossing(to);
                    w.speed = glm::length(at - *w.atFrom) / (when - w.tFrom);
                }
                done = done && w.speed;
                last[g][i] = p;
            }
        lastT = t;
        if (done) break;
    }
    const auto profiles = sim::speedProfiles();
    for (std::size_t g = 0; g < 4; ++g) {
        const sim::SpeedProfile& profile = profiles[g];
        std::vector<double> speeds;
        for (const Walk& w : walks[g])
            if (w.speed) speeds.push_back(*w.speed);
        ASSERT_EQ(speeds.size(), walks[g].size()) << profile.who << ": walkers that never crossed x = 45 m in 150 s";
        std::sort(speeds.begin(), speeds.end());
        // Kolmogorov-Smirnov: the largest distance between the measured and the drawn distribution.
        double d = 0.0;
        for (std::size_t i = 0; i < speeds.size(); ++i) {
            const double f = profile.cumulative(speeds[i]), n = double(speeds.size());
            d = std::max({d, f - double(i) / n, double(i + 1) / n - f});
        }
        const double critical = 1.628 / std::sqrt(double(speeds.size()));  // 1 % level
        std::printf("RiMEA 7, %s: %zu walkers at %.2f to %.2f m/s (table: %.2f to %.2f); KS distance %.3f (1 %% level: %.3f)\n",
                    std::string(profile.who).c_str(), speeds.size(), speeds.front(), speeds.back(), profile.lo, profile.hi, d,
                    critical);
        EXPECT_GE(speeds.front(), profile.lo - 0.01) << profile.who;
        EXPECT_LE(speeds.back(), profile.hi + 0.01) << profile.who;
        EXPECT_LT(d, critical) << profile.who << ": the measured speeds do not follow the drawn distribution";
    }
}

}  // namespace
}  // namespace throng
