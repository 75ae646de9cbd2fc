// A million steps of state that really integrates (DESIGN.md, long runs): a walker steered by
// DetourCrowd between destinations on a navigation mesh, its walk cycle's phase accumulated step by
// step. Checked against quantities computed independently in long double: the phase against the
// integral of speed over the clip's stride, the distance walked against the integral of speed, the
// time against the step count; and the walker must still be on the mesh, facing a finite way.

#include <gtest/gtest.h>

#include <cmath>

#include "throng/actors/Crowd.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/NavMesh.h"
#include "throng/sim/SimulationClock.h"

using namespace throng;
using namespace throng::sim;

TEST(LongRun, AMillionStepsOfLocomotionKeepPhaseDistanceAndTimeExact) {
    NavGeometry g;  // a 40 m square with a block in the middle: paths bend round it
    g.addBox(glm::vec3(-20, -0.5f, -20), glm::vec3(20, 0, 20), true);
    g.addBox(glm::vec3(-5, 0, -5), glm::vec3(5, 4, 5), false);
    const auto nav = NavMesh::build(g);
    auto walk = std::make_shared<Locomotion>(nav, Locomotion::Settings{});
    const auto humanoid = makeSeedHumanoid();
    Locomotion::Actor a;
    a.tmpl = humanoid;
    a.walkClip = humanoid->findClip("walk");
    a.walkClipSpeed = 1.4;
    a.speed = 1.4;
    a.start = glm::vec3(-15, 0, -15);
    Crowd crowd;
    crowd.add(humanoid, walk, walk->addActor(a));
    const double duration = humanoid->clips()[std::size_t(a.walkClip)]->duration();
    const double stride = a.walkClipSpeed * duration;  // metres per walk cycle

    SimulationClock clock;
    constexpr std::uint64_t kSteps = 1'000'000;
    long double cycles = 0.0L, integral = 0.0L, walked = 0.0L;
    glm::vec3 last(0.0f);
    for (std::uint64_t f = 0; f <= kSteps; ++f, clock.advance()) {
        const FrameContext context = clock.context();
        crowd.step(context);
        const glm::vec3 at(walk->referencePoint(0, context, nullptr)[3]);
        if (f > 0) {
            // The speed the step moved with (DetourCrowd's velocity after it) and what it covered.
            cycles += static_cast<long double>(context.deltaTime) * walk->speed(0) / stride;
            integral += static_cast<long double>(context.deltaTime) * walk->speed(0);
            const glm::vec3 d = at - last;
            walked += std::sqrt(static_cast<long double>(d.x) * d.x + static_cast<long double>(d.z) * d.z);
        }
        last = at;
        if (f % 100'000 == 0) {
            ASSERT_TRUE(std::isfinite(at.x) && std::isfinite(at.z)) << "step " << f;
            const auto onMesh = nav->nearestPoint(at, glm::vec3(0.05f, 0.5f, 0.05f));
            ASSERT_TRUE(onMesh.has_value()) << "step " << f << ": the walker left the mesh";
            ASSERT_LT(glm::length(*onMesh - at), 0.05f) << "step " << f;
        }
    }
    // Time is computed from the step count, never accumulated.
    EXPECT_EQ(clock.context().time, double(kSteps + 1) * clock.step());
    // The walk cycle's phase, accumulated in double with wrapping, against the long double integral.
    const double expected = static_cast<double>(cycles - std::floor(cycles));
    const double got = walk->clipTime(0, 0.0) / duration;
    const double error = std::abs(std::remainder(got - expected, 1.0));
    EXPECT_LT(error, 1e-6) << "walk-cycle phase after " << kSteps << " steps (" << static_cast<double>(cycles) << " cycles)";
    // The distance covered against the integral of the speed: the same to a fraction of a percent
    // (DetourCrowd snaps positions to the mesh surface, which can shorten a step at a corner).
    EXPECT_GT(static_cast<double>(integral), 0.9 * 1.4 * double(kSteps) / 60.0) << "it walked nearly all the time (4.6 hours)";
    EXPECT_NEAR(static_cast<double>(walked / integral), 1.0, 5e-3);
    RecordProperty("phaseError", std::to_string(error));
    RecordProperty("metresWalked", std::to_string(static_cast<double>(walked)));
}
