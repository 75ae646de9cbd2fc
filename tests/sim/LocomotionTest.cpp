// Navigation and locomotion: a navigation mesh from walkable slabs and obstacles, actors walking
// it with DetourCrowd (never inside an obstacle), view-independent and deterministic, with the
// avoidance effect present only when asked for.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <span>
#include <string>

#include "throng/actors/Actor.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/CounterRng.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/NavMesh.h"
#include "throng/sim/SimulationClock.h"

using namespace throng;
using namespace throng::sim;

namespace {

// A 60 m square of ground with four 8 m blocks standing on it.
NavGeometry plaza() {
    NavGeometry g;
    g.addBox(glm::vec3(-30, -0.5f, -30), glm::vec3(30, 0, 30), true);
    for (float x : {-12.0f, 12.0f})
        for (float z : {-12.0f, 12.0f}) g.addBox(glm::vec3(x - 4, 0, z - 4), glm::vec3(x + 4, 6, z + 4), false);
    return g;
}

bool insideBlock(const glm::vec3& p) {
    for (float x : {-12.0f, 12.0f})
        for (float z : {-12.0f, 12.0f})
            if (std::abs(p.x - x) < 4.0f && std::abs(p.z - z) < 4.0f) return true;
    return false;
}

struct Walkers {
    EffectCounters counters;
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::shared_ptr<Locomotion> locomotion;
};

std::unique_ptr<Walkers> walkers(const std::shared_ptr<const NavMesh>& nav, int n, bool avoidance) {
    auto w = std::make_unique<Walkers>();
    Locomotion::Settings settings;
    settings.avoidance = avoidance;
    w->locomotion = std::make_shared<Locomotion>(nav, settings, std::vector<double>{40.0, 1e9}, &w->counters);
    static const auto humanoid = makeSeedHumanoid();
    for (int i = 0; i < n; ++i) {
        Locomotion::Actor a;
        a.tmpl = humanoid;
        a.walkClip = humanoid->findClip("walk");
        a.start = nav->randomPoint(CounterRng(99, std::uint64_t(i)), 0);
        a.speed = 1.2 + 0.4 * CounterRng(7, std::uint64_t(i)).uniform(0);
        a.stream = std::uint64_t(i);
        w->root->addChild(w->crowd.makeActorNode(w->crowd.add(humanoid, w->locomotion, w->locomotion->addActor(a))));
    }
    return w;
}

}  // namespace

TEST(Navigation, BuildsAroundObstaclesAndGivesDeterministicRandomPoints) {
    const auto nav = NavMesh::build(plaza());
    EXPECT_GT(nav->polygonCount(), 4);
    const CounterRng rng(3, 1);
    for (std::uint64_t k = 0; k < 200; ++k) {
        const glm::vec3 p = nav->randomPoint(rng, k);
        EXPECT_FALSE(insideBlock(p)) << p.x << " " << p.z;
        EXPECT_NEAR(p.y, 0.0f, 0.3f);
        EXPECT_EQ(p, nav->randomPoint(rng, k)) << "a pure function of the stream and counter";
    }
    EXPECT_FALSE(nav->nearestPoint(glm::vec3(0, 50, 0)).has_value()) << "far above the mesh";
    EXPECT_THROW(NavMesh::build(NavGeometry{}), std::invalid_argument);
    NavGeometry onlyObstacles;
    onlyObstacles.addBox(glm::vec3(0), glm::vec3(5), false);
    EXPECT_THROW(NavMesh::build(onlyObstacles), std::runtime_error);
}

// A mesh sent as bytes to another process (rank 0's to the other ranks) is the same mesh there: the
// same polygons under the same references, so the same random points, nearest points and walkers.
TEST(Navigation, AMeshReadFromItsBytesIsTheSameMesh) {
    NavMeshSettings tiled;
    tiled.tileSize = 16.0f;  // several Detour tiles, each put back in its own slot
    for (const NavMeshSettings& settings : {NavMeshSettings{}, tiled}) {
        const std::shared_ptr<const NavMesh> nav = NavMesh::build(plaza(), settings);
        const std::vector<std::byte> bytes = nav->toBytes();
        const std::shared_ptr<const NavMesh> copy = NavMesh::fromBytes(bytes);
        EXPECT_EQ(copy->polygonCount(), nav->polygonCount());
        EXPECT_EQ(copy->bounds(), nav->bounds());
        EXPECT_EQ(0, std::memcmp(&copy->settings(), &settings, sizeof settings));
        EXPECT_EQ(copy->toBytes(), bytes) << "written again, the same bytes";
        const CounterRng rng(5, 2);
        for (std::uint64_t k = 0; k < 100; ++k) {
            EXPECT_EQ(copy->randomPoint(rng, k), nav->randomPoint(rng, k));
            const glm::vec3 probe(float(k % 10) * 6.0f - 30.0f, 1.0f, float(k / 10) * 6.0f - 30.0f);
            EXPECT_EQ(copy->nearestPoint(probe), nav->nearestPoint(probe));
        }
        // Walkers on the copy walk as on the original, bit for bit.
        auto a = walkers(nav, 30, true), b = walkers(copy, 30, true);
        SimulationClock clock;
        for (int f = 0; f < 60; ++f, clock.advance()) a->crowd.step(clock.context()), b->crowd.step(clock.context());
        for (std::uint32_t slot = 0; slot < 30; ++slot) {
            EXPECT_EQ(a->locomotion->position(slot), b->locomotion->position(slot)) << "walker " << slot;
            EXPECT_EQ(a->locomotion->destination(slot), b->locomotion->destination(slot)) << "walker " << slot;
        }
    }
}

// Bytes that are not a mesh's are refused, naming what is wrong; none is read past its end.
TEST(Navigation, BytesThatAreNotAMeshAreRefusedSayingWhy) {
    NavMeshSettings tiled;
    tiled.tileSize = 16.0f;
    const std::vector<std::byte> bytes = NavMesh::build(plaza(), tiled)->toBytes();
    auto refusal = [](std::span<const std::byte> b) {
        try {
            NavMesh::fromBytes(b);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("(read)");
    };
    EXPECT_NE(refusal({}).find("the bytes end at 0 inside the header"), std::string::npos) << refusal({});
    for (std::size_t cut : {std::size_t(6), std::size_t(40), bytes.size() / 2, bytes.size() - 1}) {
        const std::string why = refusal(std::span(bytes).first(cut));
        EXPECT_NE(why.find("the bytes end at " + std::to_string(cut) + " inside"), std::string::npos) << why;
    }
    std::vector<std::byte> other = bytes;
    other[0] = std::byte{'X'};
    EXPECT_NE(refusal(other).find("not a navigation mesh's bytes"), std::string::npos) << refusal(other);
    other = bytes;
    other[4] = std::byte{9};  // the version
    EXPECT_NE(refusal(other).find("version 9, this build reads version 1"), std::string::npos) << refusal(other);
    other = bytes;
    other.push_back(std::byte{0});
    EXPECT_NE(refusal(other).find("1 bytes follow the last tile"), std::string::npos) << refusal(other);
}

TEST(Locomotion, ActorsWalkTheMeshNeverThroughObstaclesAndOnlyAvoidWhenAsked) {
    const std::shared_ptr<const NavMesh> nav = NavMesh::build(plaza());
    for (bool avoidance : {false, true}) {
        auto w = walkers(nav, 40, avoidance);
        ActorProcessor p(w->crowd);
        Camera camera;
        camera.setPerspective(1.2, 1.5, 0.1, 300.0);
        camera.setLookAt(Vec3(0, 40, 60), Vec3(0.0), Vec3(0, 1, 0));
        SimulationClock clock;
        std::vector<Vec3> start;
        for (int f = 0; f < 600; ++f, clock.advance()) {
            w->crowd.step(clock.context());
            p.processFrame(*w->root, camera, clock.time());
            if (f == 0)
                for (ActorId id = 0; id < w->crowd.size(); ++id) start.push_back(Vec3(w->crowd.referencePoint(id)[3]));
            for (ActorId id = 0; id < w->crowd.size(); ++id)
                ASSERT_FALSE(insideBlock(glm::vec3(w->crowd.referencePoint(id)[3]))) << "actor " << id << " frame " << f;
        }
        double moved = 0.0;
        for (ActorId id = 0; id < w->crowd.size(); ++id) moved += glm::length(Vec3(w->crowd.referencePoint(id)[3]) - start[id]);
        EXPECT_GT(moved / double(w->crowd.size()), 3.0) << "they walk";
        EXPECT_EQ(w->counters.of("locomotion").constructed, 1u);
        EXPECT_EQ(w->counters.of("locomotion").ticks, 40u * 599u);
        EXPECT_EQ(w->counters.of("avoidance").constructed, avoidance ? 1u : 0u);
        EXPECT_EQ(w->counters.of("avoidance").ticks, avoidance ? 40u * 599u : 0u);
    }
}

TEST(Locomotion, TrajectoriesAreDeterministicAndViewIndependent) {
    const std::shared_ptr<const NavMesh> nav = NavMesh::build(plaza());
    auto run = [&](int view, unsigned threads) {
        auto w = walkers(nav, 60, true);
        ActorProcessor p(w->crowd);
        p.setThreads(threads);
        ThreadTeam team(threads);  // the step's per-agent work on as many threads
        SimulationClock clock;
        std::vector<Mat4> out;
        for (int f = 0; f < 200; ++f, clock.advance()) {
            Camera camera;
            camera.setPerspective(1.0, 1.5, 0.1, 300.0);
            camera.setLookAt(view == 0 ? Vec3(0, 30, 50) : Vec3(0, 30, 50), view == 0 ? Vec3(0.0) : Vec3(0, 30, 200), Vec3(0, 1, 0));
            team.run([&] { w->crowd.step(clock.context()); });
            p.processFrame(*w->root, camera, clock.time());
            for (ActorId id = 0; id < w->crowd.size(); ++id) out.push_back(w->crowd.referencePoint(id));
        }
        return out;
    };
    const auto looking = run(0, 1);
    const auto away = run(1, 1);
    const auto threaded = run(0, 3);
    // They walk (the comparison would prove nothing of frozen actors) ...
    const std::size_t n = looking.size() / 200;
    double moved = 0.0;
    for (std::size_t i = 0; i < n; ++i) moved += glm::length(Vec3(looking[199 * n + i][3]) - Vec3(looking[i][3]));
    EXPECT_GT(moved / double(n), 1.0);
    // ... the same whatever the camera looks at and whatever the number of threads.
    EXPECT_EQ(0, std::memcmp(looking.data(), away.data(), looking.size() * sizeof(Mat4)));
    EXPECT_EQ(0, std::memcmp(looking.data(), threaded.data(), looking.size() * sizeof(Mat4)));
}

// Phase 1 asks the walkers for runs of Reference Points at once (Behaviour::referencePoints): each
// must carry the bits of the walker's own referencePoint call, whatever run it is asked in.
TEST(Locomotion, BatchedReferencePointsEqualSingleCalls) {
    const std::shared_ptr<const NavMesh> nav = NavMesh::build(plaza());
    auto w = walkers(nav, 37, true);
    SimulationClock clock;
    for (int f = 0; f < 30; ++f, clock.advance()) w->crowd.step(clock.context());
    std::vector<std::uint32_t> slots;
    for (ActorId id = 0; id < w->crowd.size(); ++id) slots.push_back(w->crowd.state().slot[id]);
    std::reverse(slots.begin(), slots.end());
    for (std::size_t n : {std::size_t(1), std::size_t(16), std::size_t(17), slots.size()}) {
        std::vector<Mat4> out(n);
        w->locomotion->referencePoints({slots.data(), n}, clock.context(), nullptr, out);
        for (std::size_t k = 0; k < n; ++k) {
            const Mat4 single = w->locomotion->referencePoint(slots[k], clock.context(), nullptr);
            ASSERT_EQ(0, std::memcmp(&out[k], &single, sizeof(Mat4))) << "slot " << slots[k] << " in a run of " << n;
        }
    }
}
