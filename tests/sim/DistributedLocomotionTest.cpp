// Locomotion split over the ranks of a run: run plainly it is one rank (the distributed path with
// local messages); run by CTest under mpiexec (label mpi) each rank steps its own regions. Every
// rank also steps the same crowd alone, as one process would, and the two must agree bitwise: on
// rank 0 for every walker (it gathers them all), elsewhere for the walkers the rank steps.
#include <gtest/gtest.h>

#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "PlazaWalkers.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/Ranks.h"
#include "throng/sim/SimulationClock.h"

namespace throng::sim {
namespace {

// The plaza in 3 x 3 regions with 400 walkers crossing it and avoiding each other (so ghosts
// matter), as the thread-determinism test has it; with `far`, regions farther than 15 m from a
// corner step every third step only.
std::shared_ptr<Locomotion> crossing(const std::shared_ptr<const NavMesh>& nav, bool far) {
    Locomotion::Settings s;
    s.avoidance = true;
    if (far) s.farDistance = 15.0, s.farEvery = 3;
    s.regions = RegionGrid::tiled(glm::dvec2(-30.0), 20.0, 3, 3, 1, 1);
    auto walk = test::plazaWalkers(nav, s, 400, 5, true);
    walk->setViewpoint(glm::vec3(-30.0f, 2.0f, -30.0f));
    return walk;
}

// What is drawn of a walker: its Reference Point and walk-cycle time, and its region.
std::vector<float> drawnState(Locomotion& walk, std::uint32_t slot) {
    const Mat4 m = walk.referencePoint(slot, FrameContext{}, nullptr);
    std::vector<float> out;
    for (int k = 0; k < 16; ++k) out.push_back(float(m[k / 4][k % 4]));
    out.push_back(float(walk.clipTime(slot, 0.0)));
    out.push_back(float(walk.region(slot)));
    return out;
}

// Whether a walker standing at `p` lies within `margin` of every plane of `view`.
bool nearView(const Frustum& view, const glm::vec3& p, double margin) {
    for (int i = 0; i < Frustum::kPlaneCount; ++i) {
        if (!(view.activePlanes() & (1u << i))) continue;
        const Vec4& q = view.plane(i);
        if (q.x * double(p.x) + q.y * double(p.y) + q.z * double(p.z) + q.w < -margin) return false;
    }
    return true;
}

// Steps the plaza alone and split over the ranks (with `far`, far regions deferred), then compares.
// With `view`, rank 0 gathers only the walkers within 1 m of it: exactly those are known there
// (its own far from it are not either), and they are as one process has them; of those, exactly
// the walkers within half a metre are present (may be seen).
void stepsBitwiseAsOneProcess(bool far, std::optional<Frustum> view = std::nullopt) {
    const std::shared_ptr<const NavMesh> nav = test::plaza(true);
    Ranks ranks;
    const auto alone = crossing(nav, far), shared = crossing(nav, far);
    shared->distribute(ranks);
    if (view) shared->setGatherView(view, 1.0, 0.5);
    EXPECT_THROW(shared->setGatherView(view, -1.0), std::invalid_argument);
    EXPECT_THROW(shared->setGatherView(view, 1.0, 2.0), std::invalid_argument) << "a shown margin beyond the margin";
    alone->advance(FrameContext{});  // starts it (a step of no time)
    EXPECT_THROW(alone->distribute(ranks), std::logic_error) << "distribute() after the start is refused";
    SimulationClock clock;
    ThreadTeam team(2);
    std::size_t acrossRanks = 0, deferred = 0, leftOut = 0, cameBack = 0, knownOnly = 0;
    std::vector<std::uint8_t> wasPresent(alone->size(), 1);
    std::string firstMismatch;  // every rank steps all frames whatever it finds: the others wait for it
    team.run([&] {
        for (int f = 0; f < 300; ++f, clock.advance()) {
            alone->advance(clock.context());
            shared->advance(clock.context());
            if (ranks.rank() != 0 || clock.context().deltaTime <= 0.0 || !firstMismatch.empty()) continue;  // the first frame does not move
            std::uint64_t agents = 0;
            for (const auto& step : shared->rankSteps()) agents += step.agents, acrossRanks += step.handedToRanks;
            deferred += shared->lastDeferredCount();
            if (view) {  // known: the walkers near the view, whoever steps them, as one process has them
                std::size_t known = 0, shown = 0;
                for (std::uint32_t slot = 0; slot < alone->size() && firstMismatch.empty(); ++slot) {
                    const bool expected = nearView(*view, alone->position(slot), 1.0);
                    const bool seen = nearView(*view, alone->position(slot), 0.5);
                    known += shared->known(slot), shown += shared->present(slot);
                    knownOnly += shared->known(slot) && !shared->present(slot);
                    leftOut += !shared->known(slot), cameBack += shared->known(slot) && !wasPresent[slot];
                    wasPresent[slot] = shared->known(slot);
                    if (shared->known(slot) != expected)
                        firstMismatch = "frame " + std::to_string(f) + ": actor " + std::to_string(slot) + (expected ? " missing" : " sent");
                    else if (shared->present(slot) != seen)
                        firstMismatch = "frame " + std::to_string(f) + ": actor " + std::to_string(slot) + (seen ? " not" : "") + " shown";
                    else if (expected && drawnState(*shared, slot) != drawnState(*alone, slot))
                        firstMismatch = "frame " + std::to_string(f) + ": actor " + std::to_string(slot) + " differs from one process";
                }
                if (firstMismatch.empty() && (known != shared->presentCount() || shown != shared->shownCount()))
                    firstMismatch = "presentCount() or shownCount() is not the walkers known or shown";
            }
            if (shared->lastGhostCount() != alone->lastGhostCount() || shared->lastHandoverCount() != alone->lastHandoverCount() ||
                shared->lastDeferredCount() != alone->lastDeferredCount() || agents != alone->size())
                firstMismatch = "frame " + std::to_string(f) + ": " + std::to_string(shared->lastGhostCount()) + " ghosts, " +
                                std::to_string(shared->lastHandoverCount()) + " handovers and " + std::to_string(agents) +
                                " walkers stepped, against " + std::to_string(alone->lastGhostCount()) + ", " +
                                std::to_string(alone->lastHandoverCount()) + " and " + std::to_string(alone->size());
        }
    });
    EXPECT_EQ(firstMismatch, "");
    ASSERT_EQ(shared->rankSteps().size(), std::size_t(ranks.size()));
    const auto [first, end] = shared->ownRegions();
    std::size_t compared = 0;
    for (std::uint32_t slot = 0; slot < alone->size(); ++slot) {
        // Each rank's own walkers, and on rank 0 those present (the others' walkers left out of the
        // gather were compared above while present).
        const bool own = shared->region(slot) >= first && shared->region(slot) < end;
        if (!own && (ranks.rank() != 0 || !shared->present(slot))) continue;
        const std::vector<float> a = drawnState(*alone, slot), b = drawnState(*shared, slot);
        for (std::size_t k = 0; k < a.size(); ++k)
            ASSERT_EQ(std::memcmp(&a[k], &b[k], sizeof(float)), 0)
                << "actor " << slot << " on rank " << ranks.rank() << ", value " << k << ": " << a[k] << " alone, " << b[k] << " shared";
        ++compared;
    }
    EXPECT_GT(compared, 0u);
    if (ranks.rank() == 0 && far) {
        EXPECT_GT(deferred, 1000u) << "far regions should have waited for their turn";
    }
    if (ranks.rank() == 0 && ranks.size() > 1) {
        EXPECT_GT(acrossRanks, 10u) << "walkers should cross from one rank's regions to another's, or the test proves little";
        if (view) {
            EXPECT_GT(leftOut, 1000u) << "the view should leave walkers out";
            EXPECT_GT(cameBack, 4u) << "walkers should come back near the view (" << leftOut << " left out)";
            EXPECT_GT(knownOnly, 4u) << "some walkers should be known but not shown (between half a metre and a metre out)";
        }
    }
}

}  // namespace

// Plain tests, not parameterised ones: those would run after RanksTest's, the last of which leaves
// a rank silent.
TEST(DistributedLocomotion, StepsBitwiseAsOneProcess) { stepsBitwiseAsOneProcess(false); }
TEST(DistributedLocomotion, StepsBitwiseAsOneProcessWithFarRegionsDeferred) { stepsBitwiseAsOneProcess(true); }
// Rank 0 gathers only the walkers near a view over one corner of the plaza.
TEST(DistributedLocomotion, GathersOnlyTheWalkersNearTheView) {
    Camera camera;
    camera.setPerspective(0.7, 1.5, 0.5, 35.0);
    camera.setLookAt(Vec3(-32.0, 8.0, -32.0), Vec3(-5.0, 0.0, -5.0), Vec3(0.0, 1.0, 0.0));
    stepsBitwiseAsOneProcess(false, camera.frustum());
}

}  // namespace throng::sim
