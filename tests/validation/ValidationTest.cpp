// Do the walkers move like people? Scenarios of the RiMEA guideline (version 3) for the
// verification of pedestrian simulations, each a small scene file in tests/validation/scenes, run
// through the Simulation as throng-town runs it, each asserting the guideline's acceptance:
//
//   * RiMEA 1: one walker at 1.33 m/s along a 2 m x 40 m corridor arrives in 26 to 34 s. The same
//     walker made 30 % faster must fail the same check (the test can fail).
//   * RiMEA 4: the fundamental diagram. A periodic corridor 2 m x 20 m (walkers 0.4 m across) held
//     at 0.5, 1, 2, 3, 4 and 5 persons/m^2; after 10 s, speed and density measured for 20 s in its
//     middle 8 m and compared with Weidmann's v(rho) = 1.34 (1 - exp(-1.913 (1/rho - 1/5.4))).
//     Accepted: within 0.25 m/s of the curve up to 2 persons/m^2 (Weidmann's fit runs through data
//     scattered about that much); the denser points are reported. DetourCrowd fails it (its walkers
//     keep about 1 m/s at every density, pushing through each other above 3 persons/m^2): a known
//     failure, as below.
//   * RiMEA 6: 20 walkers turn a 90 degree corner (corridors 2 m wide): every one arrives round it
//     within 60 s, no body crosses a wall, and the share of agent-seconds with bodies
//     interpenetrating by more than 5 cm stays under 2 %.
//   * RiMEA 7: four populations of 50 walkers each with the guideline's free speeds (after Weidmann
//     1993), walking without interaction: every walker's measured speed lies in its population's
//     range, and each population's speeds follow the distribution drawn from (Kolmogorov-Smirnov,
//     1 % level).
//   * Bottleneck (Seyfried et al. 2009, Kretz et al. 2006): 60 walkers (0.44 m across) leave a room
//     through a corridor 2 m long, 0.8, 1.0 and 1.2 m wide, five runs each (the scene's seed and the
//     next four): in every run all through within 120 s and bodies overlapping under 2 %; the mean
//     specific flow within 1.4 to 2.2 persons/(m s) (the experiments' 1.6 to 2.0 widened by their own
//     spread). The scene's navigation cells are 2 cm: the mesh is eroded by whole cells, and 5 cm cells
//     would take 0.25 m off each side of the door for a 0.22 m body, 17 % of the 0.8 m door's room
//     for walkers' centres. DetourCrowd fails it (everyone through, but 2.5 persons/(m s) through the
//     wider doors with bodies pushed through each other in 2 to 4 % of agent-seconds): a known failure.
//   * Counter-flow: two groups of 30 walk at each other along a corridor 4 m wide: every walker
//     passes the other group within 90 s (no deadlock), and lanes form: the lane order parameter
//     (below) of the walkers between the groups' starts exceeds 0.5 while they pass. DetourCrowd
//     fails it (one walker stuck, bodies overlapping in 10 % of agent-seconds): a known failure,
//     skipped in the suite, run and reported when THRONG_VALIDATION_KNOWN_FAILURES=1 (the results
//     page's script sets it).
//
// Every scenario runs for both avoidance models (the scene's effects.avoidance.model): DetourCrowd
// and ORCA (sim/OrcaSolver on Detour's path corridors, each walker slowed to Weidmann's speed for the
// density ahead of it, walkers held back abreast giving way by a right of way). Each prints what it measured (the figures the results page reports).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

// The avoidance model every scenario of the running test uses ("detour" or "orca": the test's
// parameter, set by the fixture).
std::string gModel = "detour";

// Every scenario runs once per avoidance model.
class Validation : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override { gModel = GetParam(); }
    // Whether this model fails the scenario as a known failure (DetourCrowd's, or both models' when
    // `orcaToo`), skipped in the suite unless THRONG_VALIDATION_KNOWN_FAILURES is set.
    static bool skipKnownFailure(bool orcaToo = false) {
        return (gModel == "detour" || orcaToo) && !std::getenv("THRONG_VALIDATION_KNOWN_FAILURES");
    }
};

// A scenario's world and its walkers, group by group.
class Scenario {
public:
    explicit Scenario(const std::string& file, const std::function<void(sim::SceneDescription&)>& edit = {}) {
        sim::SceneDescription scene = sim::parseSceneFile(kScenes + "/" + file);
        if (edit) edit(scene);
        scene.effects.avoidanceModel = gModel;
        floors_ = scene.walkways->floors;
        bodyRadius_ = scene.walkways->bodyRadius;
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
    double bodyRadius() const { return bodyRadius_; }
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
    double bodyRadius_ = 0.35;
    std::unique_ptr<sim::Simulation> world_;
    std::vector<std::vector<std::uint32_t>> slots_;
};

// Bodies interpenetrating: each step, every counted walker whose disc overlaps another's by more
// than `depth` adds the step's time to the overlapping agent-seconds.
struct OverlapMeter {
    double radius = 0.35;  // the walkers' body radius
    double depth = 0.05;
    double agentSeconds = 0.0, overlappingSeconds = 0.0, deepest = 0.0;

    void add(const std::vector<glm::vec3>& bodies, double dt) {
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            double worst = 0.0;
            for (std::size_t j = 0; j < bodies.size(); ++j) {
                if (i == j) continue;
                const double dx = bodies[i].x - bodies[j].x, dz = bodies[i].z - bodies[j].z;
                worst = std::max(worst, 2.0 * radius - std::sqrt(dx * dx + dz * dz));
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

TEST_P(Validation, Rimea1KeepsSpeedInCorridor) {
    Scenario s("rimea1-corridor.json");
    const auto t = rimea1Time(s);
    ASSERT_TRUE(t) << "the walker never reached the corridor's end";
    std::printf("RiMEA 1: 40 m in %.2f s (accepted: 26 to 34 s; 1.33 m/s gives 30.1 s)\n", *t);
    RecordProperty("seconds", std::to_string(*t));
    EXPECT_GE(*t, 26.0);
    EXPECT_LE(*t, 34.0);
}

TEST_P(Validation, Rimea1FailsForAWalker30PercentFaster) {
    Scenario s("rimea1-corridor.json", [](sim::SceneDescription& d) { d.actors[0].speed = glm::dvec2(1.33 * 1.3); });
    const auto t = rimea1Time(s);
    ASSERT_TRUE(t);
    std::printf("RiMEA 1 at 1.73 m/s: 40 m in %.2f s, outside 26 to 34 s as it must be\n", *t);
    RecordProperty("seconds", std::to_string(*t));
    EXPECT_LT(*t, 26.0) << "a walker 30 % faster than the guideline's passed its check: the check cannot fail";
}

// Weidmann's speed at density `rho` (persons/m^2), m/s.
double weidmann(double rho) { return 1.34 * (1.0 - std::exp(-1.913 * (1.0 / rho - 1.0 / 5.4))); }

struct DensityPoint {
    double declared = 0.0, measuredDensity = 0.0, speed = 0.0, overlapShare = 0.0;
};

// The corridor held at `rho` persons/m^2: the mean density and speed in its middle 8 m.
DensityPoint fundamentalDiagramPoint(double rho) {
    Scenario s("rimea4-fundamental-diagram.json", [&](sim::SceneDescription& d) { d.actors[0].count = std::int64_t(std::lround(rho * 40.0)); });
    const auto& walkers = s.group(0);
    OverlapMeter overlaps{s.bodyRadius()};
    while (s.time() < 10.0) s.step();
    std::vector<glm::vec3> before(walkers.size());
    double densitySum = 0.0, distance = 0.0, walkerSeconds = 0.0;
    int samples = 0;
    const double every = 0.5;
    for (std::size_t i = 0; i < walkers.size(); ++i) before[i] = s.position(walkers[i]);
    double next = s.time() + every;
    while (s.time() < 30.0) {
        s.step();
        std::vector<glm::vec3> all;
        for (std::uint32_t slot : walkers) all.push_back(s.position(slot));
        overlaps.add(all, s.stepSeconds());
        if (s.time() + 1e-9 < next) continue;
        next += every;
        int inside = 0;
        for (std::size_t i = 0; i < walkers.size(); ++i) {
            const glm::vec3 p = all[i], q = before[i];
            if (p.x >= 6.0f && p.x <= 14.0f) ++inside;
            if (q.x >= 6.0f && q.x <= 14.0f && p.x > q.x - 1.0f && p.x < q.x + 2.0f) {  // in the middle, not across the seam
                distance += p.x - q.x;
                walkerSeconds += every;
            }
            before[i] = p;
        }
        densitySum += inside / 16.0;
        ++samples;
    }
    return {rho, densitySum / samples, walkerSeconds > 0.0 ? distance / walkerSeconds : 0.0, overlaps.share()};
}

TEST_P(Validation, Rimea4FundamentalDiagram) {
    if (skipKnownFailure())
        GTEST_SKIP() << "a known failure of DetourCrowd's avoidance (about 1 m/s at every density from 0.5 to 5 persons/m^2): "
                        "run with THRONG_VALIDATION_KNOWN_FAILURES=1";
    for (double rho : {0.5, 1.0, 2.0, 3.0, 4.0, 5.0}) {
        const DensityPoint p = fundamentalDiagramPoint(rho);
        const double expected = weidmann(p.measuredDensity);
        std::printf("RiMEA 4 at %.1f persons/m^2: measured %.2f persons/m^2, %.3f m/s (Weidmann: %.3f); overlapping by more "
                    "than 5 cm: %.2f %%\n", rho, p.measuredDensity, p.speed, expected, 100.0 * p.overlapShare);
        const std::string key = "rho_" + std::to_string(int(std::lround(rho * 10)));
        RecordProperty(key + "_density", std::to_string(p.measuredDensity));
        RecordProperty(key + "_speed", std::to_string(p.speed));
        RecordProperty(key + "_weidmann", std::to_string(expected));
        RecordProperty(key + "_overlap_share", std::to_string(p.overlapShare));
        if (rho <= 2.0) {
            EXPECT_NEAR(p.speed, expected, 0.25) << "at " << rho << " persons/m^2";
        }
    }
}

TEST_P(Validation, Rimea6TurnsTheCorner) {
    Scenario s("rimea6-corner.json");
    const auto& walkers = s.group(0);
    ASSERT_EQ(walkers.size(), 20u);
    const double arrival = 8.0;  // z of the line 6 m round the corner
    std::vector<double> arrived(walkers.size(), -1.0);
    OverlapMeter overlaps{s.bodyRadius()};
    std::size_t offFloor = 0;
    while (s.time() < 60.0 && std::count(arrived.begin(), arrived.end(), -1.0) > 0) {
        s.step();
        std::vector<glm::vec3> turning;  // walkers not yet round the corner
        for (std::size_t i = 0; i < walkers.size(); ++i) {
            const glm::vec3 p = s.position(walkers[i]);
            if (!s.bodyOnFloors(p, s.bodyRadius() - 0.05)) ++offFloor;
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
    RecordProperty("arrived", std::to_string(walkers.size() - std::size_t(missing)));
    RecordProperty("last_arrival_s", std::to_string(last));
    RecordProperty("off_floor_steps", std::to_string(offFloor));
    RecordProperty("overlap_share", std::to_string(overlaps.share()));
    RecordProperty("deepest_overlap_m", std::to_string(overlaps.deepest));
    EXPECT_EQ(missing, 0) << "walkers still before the corner after 60 s";
    EXPECT_EQ(offFloor, 0u) << "a body crossed a wall";
    EXPECT_LT(overlaps.share(), 0.02);
}

TEST_P(Validation, Rimea7SpeedsFollowThePopulations) {
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
        const std::string key(profile.name);
        RecordProperty(key + "_min", std::to_string(speeds.front()));
        RecordProperty(key + "_max", std::to_string(speeds.back()));
        RecordProperty(key + "_ks", std::to_string(d));
        RecordProperty(key + "_ks_critical", std::to_string(critical));
        EXPECT_GE(speeds.front(), profile.lo - 0.01) << profile.who;
        EXPECT_LE(speeds.back(), profile.hi + 0.01) << profile.who;
        EXPECT_LT(d, critical) << profile.who << ": the measured speeds do not follow the drawn distribution";
    }
}

// Bottleneck: the specific flow through the corridor of `width` metres (its floor resized), measured
// where the walkers cross its middle: passages 10 to 50 of 60, persons per metre and second; with the
// time the last walker crossed.
struct BottleneckRun {
    double specificFlow = 0.0, lastCrossing = -1.0;
    std::size_t crossed = 0;
    double overlapShare = 0.0, deepest = 0.0;
};

BottleneckRun runBottleneck(double width, std::uint64_t seedOffset) {
    Scenario s("bottleneck.json", [&](sim::SceneDescription& d) {
        d.walkways->floors.at(1).size.y = width;
        d.seed += seedOffset;
    });
    const auto& walkers = s.group(0);
    std::vector<glm::vec3> last;
    for (std::uint32_t slot : walkers) last.push_back(s.position(slot));
    std::vector<double> crossings;
    std::vector<char> done(walkers.size(), 0);
    OverlapMeter overlaps{s.bodyRadius()};
    double lastT = 0.0;
    while (s.time() < 120.0 && crossings.size() < walkers.size()) {
        s.step();
        std::vector<glm::vec3> before;
        for (std::size_t i = 0; i < walkers.size(); ++i) {
            const glm::vec3 p = s.position(walkers[i]);
            if (!done[i] && last[i].x < 9.0f && p.x >= 9.0f) {
                crossings.push_back(lastT + (s.time() - lastT) * (9.0 - last[i].x) / (p.x - last[i].x));
                done[i] = 1;
            }
            if (!done[i]) before.push_back(p);
            last[i] = p;
        }
        overlaps.add(before, s.stepSeconds());
        lastT = s.time();
    }
    BottleneckRun r;
    r.crossed = crossings.size();
    std::sort(crossings.begin(), crossings.end());
    if (crossings.size() > 50) r.specificFlow = 40.0 / (crossings[49] - crossings[9]) / width;
    if (!crossings.empty()) r.lastCrossing = crossings.back();
    r.overlapShare = overlaps.share(), r.deepest = overlaps.deepest;
    return r;
}

TEST_P(Validation, BottleneckFlowMatchesExperiments) {
    if (skipKnownFailure())
        GTEST_SKIP() << "a known failure of DetourCrowd's avoidance (at 0.8 m three walkers clog the door for good, 2 to 4 % of "
                        "agent-seconds overlapping): run with THRONG_VALIDATION_KNOWN_FAILURES=1";
    // One run's flow depends on who reaches the door first (the walkers' places and speeds are drawn
    // from the scene's seed): each width is run kRuns times, the scene's seed and the next ones, and
    // their mean compared with the experiments, which are themselves means over runs.
    constexpr int kRuns = 5;
    for (double width : {0.8, 1.0, 1.2}) {
        double flowSum = 0.0, flowMin = 1e9, flowMax = 0.0, overlapMax = 0.0;
        std::size_t fewest = 60;
        for (int run = 0; run < kRuns; ++run) {
            const BottleneckRun r = runBottleneck(width, std::uint64_t(run));
            std::printf("Bottleneck %.1f m, run %d: %zu of 60 through, the last after %.1f s; specific flow %.2f persons/(m s); "
                        "overlapping by more than 5 cm: %.3f %%, deepest %.3f m\n",
                        width, run + 1, r.crossed, r.lastCrossing, r.specificFlow, 100.0 * r.overlapShare, r.deepest);
            flowSum += r.specificFlow, flowMin = std::min(flowMin, r.specificFlow), flowMax = std::max(flowMax, r.specificFlow);
            overlapMax = std::max(overlapMax, r.overlapShare), fewest = std::min(fewest, r.crossed);
            EXPECT_EQ(r.crossed, 60u) << width << " m, run " << run + 1 << ": walkers left behind after 120 s";
            EXPECT_LT(r.overlapShare, 0.02) << width << " m, run " << run + 1;
        }
        const double flow = flowSum / kRuns;
        std::printf("Bottleneck %.1f m: specific flow %.2f persons/(m s), the mean of %d runs (%.2f to %.2f; experiments: about "
                    "1.6 to 2.0); at least %zu of 60 through; overlapping by more than 5 cm: at most %.3f %%\n",
                    width, flow, kRuns, flowMin, flowMax, fewest, 100.0 * overlapMax);
        const std::string key = "width_" + std::to_string(int(std::lround(width * 10)));
        RecordProperty(key + "_specific_flow", std::to_string(flow));
        RecordProperty(key + "_flow_min", std::to_string(flowMin));
        RecordProperty(key + "_flow_max", std::to_string(flowMax));
        RecordProperty(key + "_overlap_share", std::to_string(overlapMax));
        RecordProperty(key + "_through", std::to_string(fewest));
        // The experiments' 1.6 to 2.0, widened by 0.2 each way: about how far apart the experiments
        // themselves lie (Seyfried et al. 2009, Kretz et al. 2006).
        EXPECT_GE(flow, 1.4) << width << " m";
        EXPECT_LE(flow, 2.2) << width << " m";
    }
}

// Lane order: for each walker, those walking the same way (+1) or the other way (-1) within 0.5 m
// across and 3 m along it; its order is ((same - other) / (same + other))^2, 1 in a lane of its own
// kind, about 0 in a mixed crowd; the mean over walkers with anyone near (nullopt: nobody near anyone).
std::optional<double> laneOrder(const std::vector<glm::vec3>& bodies, const std::vector<int>& direction) {
    double sum = 0.0;
    int counted = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        int same = 0, other = 0;
        for (std::size_t j = 0; j < bodies.size(); ++j)
            if (j != i && std::abs(bodies[j].z - bodies[i].z) < 0.5f && std::abs(bodies[j].x - bodies[i].x) < 3.0f)
                (direction[j] == direction[i] ? same : other) += 1;
        if (same + other == 0) continue;
        const double f = double(same - other) / double(same + other);
        sum += f * f;
        ++counted;
    }
    return counted ? std::optional<double>(sum / counted) : std::nullopt;
}

TEST_P(Validation, CounterFlowFormsLanesWithoutDeadlock) {
    if (skipKnownFailure())
        GTEST_SKIP() << "a known failure of DetourCrowd's avoidance (a walker stuck, 10 % of agent-seconds overlapping): "
                        "run with THRONG_VALIDATION_KNOWN_FAILURES=1";
    Scenario s("counterflow.json");
    const auto& east = s.group(0);
    const auto& west = s.group(1);
    std::vector<double> passed(east.size() + west.size(), -1.0);
    OverlapMeter overlaps{s.bodyRadius()};
    double peakOrder = 0.0, orderSum = 0.0;
    int orderSamples = 0;
    while (s.time() < 90.0 && std::count(passed.begin(), passed.end(), -1.0) > 0) {
        s.step();
        std::vector<glm::vec3> middle, passing;
        std::vector<int> direction;
        for (std::size_t i = 0; i < passed.size(); ++i) {
            const bool eastward = i < east.size();
            const glm::vec3 p = s.position(eastward ? east[i] : west[i - east.size()]);
            if (passed[i] < 0.0 && (eastward ? p.x >= 22.0f : p.x <= 8.0f)) passed[i] = s.time();
            if (passed[i] < 0.0) passing.push_back(p);
            if (p.x > 8.0f && p.x < 22.0f) middle.push_back(p), direction.push_back(eastward ? 1 : -1);
        }
        overlaps.add(passing, s.stepSeconds());
        if (middle.size() >= 10 && std::count(direction.begin(), direction.end(), 1) >= 3 &&
            std::count(direction.begin(), direction.end(), -1) >= 3)
            if (const auto order = laneOrder(middle, direction)) {
                peakOrder = std::max(peakOrder, *order);
                orderSum += *order;
                ++orderSamples;
            }
    }
    const auto stuck = std::count(passed.begin(), passed.end(), -1.0);
    const double mean = orderSamples ? orderSum / orderSamples : 0.0;
    std::printf("Counter-flow: %zu of %zu passed the other group, the last after %.1f s; lane order while they pass: mean %.2f, "
                "peak %.2f over %d steps; overlapping by more than 5 cm: %.3f %% of %.0f agent-seconds, deepest %.3f m\n",
                passed.size() - std::size_t(stuck), passed.size(), *std::max_element(passed.begin(), passed.end()), mean,
                peakOrder, orderSamples, 100.0 * overlaps.share(), overlaps.agentSeconds, overlaps.deepest);
    RecordProperty("passed", std::to_string(passed.size() - std::size_t(stuck)));
    RecordProperty("last_passed_s", std::to_string(*std::max_element(passed.begin(), passed.end())));
    RecordProperty("lane_order_mean", std::to_string(mean));
    RecordProperty("overlap_share", std::to_string(overlaps.share()));
    RecordProperty("deepest_overlap_m", std::to_string(overlaps.deepest));
    EXPECT_EQ(stuck, 0) << "walkers still stuck behind the other group after 90 s: a deadlock";
    EXPECT_GT(orderSamples, 0) << "the groups never met";
    EXPECT_GT(mean, 0.5) << "no lanes formed";
    EXPECT_LT(overlaps.share(), 0.02);
}

INSTANTIATE_TEST_SUITE_P(Models, Validation, ::testing::Values(std::string("detour"), std::string("orca")),
                         [](const ::testing::TestParamInfo<std::string>& model) { return model.param; });

}  // namespace
}  // namespace throng
