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

// Posing where stepped (Locomotion::setPosedWhereStepped): each rank shows only its own walkers near
// the view, every walker near it on exactly one rank, and knows the others' near it (to look at);
// the byte a rank keeps with each walker it poses goes with the walker to the rank that takes it over.
void eachRankShowsItsOwnWalkers(const Frustum& view) {
    const std::shared_ptr<const NavMesh> nav = test::plaza(true);
    Ranks ranks;
    const auto alone = crossing(nav, false), shared = crossing(nav, false);
    EXPECT_THROW(alone->setPosedWhereStepped(true), std::logic_error) << "posing where stepped needs ranks";
    shared->distribute(ranks);
    shared->setPosedWhereStepped(true);
    SimulationClock clock;
    std::string firstMismatch;
    std::size_t carriedOver = 0, shownOnRanks = 0, knownOthers = 0;
    // The byte each walker carries: its slot and the frame it was last posed in.
    auto keepsake = [](std::uint32_t slot, int f) { return std::uint8_t((slot * 7u + std::uint32_t(f)) & 0xffu); };
    std::vector<int> posedIn(alone->size(), -1);    // per walker: the frame this rank last set its byte
    std::vector<int> lastShown(alone->size(), -1);  // per walker: the last frame any rank showed it
    for (int f = 0; f < 200; ++f, clock.advance()) {
        if (ranks.rank() == 0) shared->setGatherView(view, 1.0, 0.5);
        alone->advance(clock.context());
        shared->advance(clock.context());
        // The walkers this rank shows: its own within half a metre of the view, as one process has them.
        const auto listed = shared->presentSlots();
        if (!listed) {
            firstMismatch = "frame " + std::to_string(f) + ": no walker listed";
            break;
        }
        std::vector<std::uint32_t> mine(listed->begin(), listed->end());
        const auto [first, end] = shared->ownRegions();
        for (std::uint32_t slot : mine) {
            if (!firstMismatch.empty()) break;
            if (shared->region(slot) < first || shared->region(slot) >= end || !nearView(view, alone->position(slot), 0.5) ||
                drawnState(*shared, slot) != drawnState(*alone, slot))
                firstMismatch = "frame " + std::to_string(f) + ": rank " + std::to_string(ranks.rank()) + " shows walker " +
                                std::to_string(slot) + ", not its own near the view as one process has it";
            // It carries what the rank that showed it last kept with it, whichever rank that was.
            else if (lastShown[slot] >= 0 && shared->carried(slot) != keepsake(slot, lastShown[slot]))
                firstMismatch = "frame " + std::to_string(f) + ": walker " + std::to_string(slot) + " carries " +
                                std::to_string(shared->carried(slot)) + ", not what frame " + std::to_string(lastShown[slot]) + " kept";
            carriedOver += lastShown[slot] >= 0 && posedIn[slot] != lastShown[slot];  // kept by another rank
        }
        for (std::uint32_t slot = 0; slot < alone->size(); ++slot)
            if (shared->known(slot) && !shared->present(slot) && nearView(view, alone->position(slot), 0.5)) ++knownOthers;
        shownOnRanks += mine.size();
        for (std::uint32_t slot : mine) shared->setCarried(slot, keepsake(slot, f)), posedIn[slot] = f;
        for (std::uint32_t slot = 0; slot < alone->size(); ++slot)
            if (nearView(view, alone->position(slot), 0.5)) lastShown[slot] = f;
        // Every walker near the view is shown by exactly one rank.
        Bytes bytes(mine.size() * sizeof(std::uint32_t));
        if (!mine.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
        const std::vector<Bytes> all = ranks.gather(bytes, 310, "shown walkers");
        if (ranks.rank() != 0) continue;
        std::vector<int> shownBy(alone->size(), 0);
        for (const Bytes& b : all)
            for (std::uint32_t slot : unpackRecords<std::uint32_t>(b, 0, "shown walkers")) ++shownBy[slot];
        for (std::uint32_t slot = 0; slot < alone->size() && firstMismatch.empty(); ++slot)
            if (shownBy[slot] != (nearView(view, alone->position(slot), 0.5) ? 1 : 0))
                firstMismatch = "frame " + std::to_string(f) + ": walker " + std::to_string(slot) + " shown by " +
                                std::to_string(shownBy[slot]) + " ranks";
    }
    EXPECT_EQ(firstMismatch, "");
    EXPECT_GT(shownOnRanks, 1000u);
    if (ranks.size() > 1) {
        EXPECT_GT(knownOthers, 100u) << "the others' walkers near the view are known (to be looked at), not shown";
        const std::vector<Bytes> counts = ranks.gather(packRecords(std::span<const std::size_t>(&carriedOver, 1)), 311, "carried");
        if (ranks.rank() == 0) {
            std::size_t total = 0;
            for (const Bytes& b : counts) total += unpackRecords<std::size_t>(b, 0, "carried")[0];
            EXPECT_GT(total, 4u) << "walkers posed by one rank should come to another with their byte";
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
// Each rank poses the walkers it steps: it shows its own near the view, and a walker's byte moves with it.
TEST(DistributedLocomotion, EachRankShowsItsOwnWalkersWhenPosingWhereStepped) {
    Camera camera;
    camera.setPerspective(0.9, 1.5, 0.5, 60.0);
    camera.setLookAt(Vec3(-32.0, 10.0, -32.0), Vec3(0.0, 0.0, 0.0), Vec3(0.0, 1.0, 0.0));
    eachRankShowsItsOwnWalkers(camera.frustum());
}

}  // namespace throng::sim
