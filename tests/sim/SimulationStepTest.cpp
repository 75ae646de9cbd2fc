// The explicit simulation step: the world advances once per Simulation::step(), whatever the
// processors of the frame do, so walkers move at the speed the scene gives them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "throng/testkit/Assets.h"
#include "throng/actors/ActorDrawReferences.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/sim/Ranks.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/NavMesh.h"
#include "throng/sim/SceneError.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"

using namespace throng;

namespace {

// Walkers in a small town at one speed, without avoidance (nothing slows them but turns and stops).
std::unique_ptr<sim::Simulation> walkers() {
    const char* text = R"({
      "name": "walkers at 1.2 m/s",
      "seed": 3,
      "town": {"blocksX": 2, "blocksZ": 2, "blockTiles": 3, "tileSize": 8, "seed": 5, "tiles": "town/kenney_city_builder"},
      "templates": {"person": {"procedural": "seed-humanoid", "walkClip": "walk"}},
      "actors": [{"name": "walkers", "template": "person", "count": 60, "behaviour": "walk", "speed": [1.2, 1.2]}],
      "camera": {"fov": 60, "near": 0.2, "far": 500, "path": [{"time": 0, "eye": [0, 40, 60], "target": [0, 0, 0]}]}
    })";
    return sim::Simulation::build(sim::parseScene(text, testkit::sharedAssets()));
}

// Each walker's distance covered per step over `steps` steps, with `processors` processors (of both
// methods) processing every frame in between, as a benchmark comparing methods would.
std::vector<double> stepLengths(int processors, int steps) {
    auto world = walkers();
    std::vector<std::unique_ptr<ActorProcessor>> p;
    for (int k = 0; k < processors; ++k) {
        p.push_back(std::make_unique<ActorProcessor>(world->crowd()));
        p.back()->setProcessing(k % 2 ? Processing::Traditional : Processing::Actor);
    }
    const Camera camera = world->camera().at(0.0, 1.5);
    std::vector<Vec3> last;
    std::vector<double> lengths;
    for (int f = 0; f < steps; ++f) {
        const double t = world->step().time;
        for (auto& processor : p) processor->processFrame(world->root(), camera, t);
        // Reference Points as the simulation has them (phase 1 of any processor reads the same).
        const Crowd::State& s = world->crowd().state();
        std::vector<Vec3> now;
        for (ActorId id = 0; id < world->crowd().size(); ++id)
            now.push_back(Vec3(s.behaviour[id]->referencePoint(s.slot[id], world->now(), nullptr)[3]));
        if (!last.empty())
            for (std::size_t i = 0; i < now.size(); ++i) {
                const Vec3 d = now[i] - last[i];  // on the ground: kerbs and slopes move walkers up and down too
                lengths.push_back(std::sqrt(d.x * d.x + d.z * d.z));
            }
        last = now;
    }
    return lengths;
}

}  // namespace

TEST(SimulationStep, WalkersMoveAtTheScenesSpeedHoweverManyProcessorsRun) {
    const double dt = 1.0 / 60.0, speed = 1.2;
    const int steps = 600;
    const std::vector<double> alone = stepLengths(0, steps);
    const std::vector<double> withThree = stepLengths(3, steps);
    ASSERT_EQ(alone.size(), withThree.size());
    std::vector<double> sorted = alone;
    std::sort(sorted.begin(), sorted.end());
    auto quantile = [&](double q) { return sorted[std::size_t(q * double(sorted.size() - 1))] / dt; };
    double sum = 0.0;
    for (double l : alone) sum += l;
    const double mean = sum / double(alone.size()) / dt;
    // Walkers walk at the speed they were given (DetourCrowd never sets a velocity above it) ...
    EXPECT_NEAR(quantile(0.5), speed, 0.01 * speed);
    // ... except for the rare step where overlapping agents are pushed apart or a corner is cut
    // (without avoidance, 60 walkers in four blocks: about 1 % of steps, more or less with the seed).
    EXPECT_LE(quantile(0.98), 1.01 * speed);
    // Turns and new destinations slow them a little on average.
    EXPECT_GT(mean, 0.9 * speed);
    EXPECT_LE(mean, 1.01 * speed);
    // Processors do not advance the simulation: the same steps, to the bit, with three of them.
    for (std::size_t i = 0; i < alone.size(); ++i) ASSERT_EQ(alone[i], withThree[i]) << "step length " << i;
}

TEST(SimulationStep, TimeAdvancesByTheFixedStepFromZero) {
    auto world = walkers();
    EXPECT_EQ(world->step().time, 0.0);
    EXPECT_EQ(world->step().time, world->description().step);
    for (int i = 0; i < 998; ++i) world->step();
    EXPECT_EQ(world->now().frame, 1000u - 1u);
    EXPECT_EQ(world->now().time, 999.0 * world->description().step);  // computed, never accumulated
    EXPECT_EQ(world->crowd().steps(), 1000u);
    EXPECT_THROW(world->setThreads(0), std::invalid_argument);
}

TEST(SimulationStep, ACrowdRefusesToStepBackInTime) {
    auto world = walkers();
    world->step();
    world->step();
    FrameContext back = world->now();
    back.time -= 1.0;
    EXPECT_THROW(world->crowd().step(back), std::invalid_argument);
    back.time = std::nan("");
    EXPECT_THROW(world->crowd().step(back), std::invalid_argument);
}

// Key-pose caches come only from the scene's declaration: one per template in use that it names,
// fresh at each call (a cache serves one processor); a template that cannot be cached is an error
// naming it in the scene.
TEST(SimulationKeyPoseCaches, OnePerDeclaredTemplateInUseAndNoneUndeclared) {
    const std::string base = R"({
      "seed": 3,
      "town": {"blocksX": 2, "blocksZ": 2, "blockTiles": 3, "tileSize": 8, "seed": 5, "tiles": "town/kenney_city_builder"},
      "templates": {"cesium": {"gltf": "characters/CesiumMan.glb"}, "person": {"procedural": "seed-humanoid", "walkClip": "walk"}},
      "actors": [{"template": "cesium", "count": 20, "behaviour": "walk"}, {"template": "cesium", "count": 6, "behaviour": "idle"},
                 {"template": "person", "count": 4, "behaviour": "walk"}])";
    auto plain = sim::Simulation::build(sim::parseScene(base + "}", testkit::sharedAssets()));
    EXPECT_TRUE(plain->makeKeyPoseCaches().empty());
    EXPECT_EQ(plain->effects().of("key-pose cache").constructed, 0u);

    auto cached = sim::Simulation::build(sim::parseScene(
        base + R"(, "representation": {"keyPoseCache": {"mode": "interpolative", "rows": {"cesium": 24}}}})", testkit::sharedAssets()));
    const auto caches = cached->makeKeyPoseCaches();
    std::size_t cesiums = 0;  // templates in use named cesium (a standing copy counts apart when it has its own clip)
    for (const auto& t : cached->templates()) cesiums += t.name.rfind("cesium", 0) == 0;
    ASSERT_GE(cesiums, 1u);
    ASSERT_EQ(caches.size(), cesiums) << "one cache per template in use of the name declared, none for person";
    EXPECT_EQ(cached->effects().of("key-pose cache").constructed, cesiums);
    for (const auto& c : caches) {
        EXPECT_EQ(c->rowCount(), 24u);
        EXPECT_EQ(c->settings().mode, KeyPoseMode::Interpolative);
    }
    EXPECT_NE(caches[0].get(), cached->makeKeyPoseCaches()[0].get()) << "each call builds fresh caches";

    auto rigid = sim::Simulation::build(
        sim::parseScene(base + R"(, "representation": {"keyPoseCache": {"rows": {"person": 8}}}})", testkit::sharedAssets()));
    try {
        rigid->makeKeyPoseCaches();
        FAIL() << "a template of rigid parts was cached";
    } catch (const sim::SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("/representation/keyPoseCache/rows/person"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("no skinned actor-level mesh"), std::string::npos) << e.what();
    }
}

namespace {

// A small town with standing people, walkers of two templates between them and birds, walkers
// gazing and with faces: what the worlds of the ranks (Scope::Walkers, Scope::Actors) must agree on.
std::string mixedTown() {
    return R"({
      "seed": 8,
      "town": {"blocksX": 2, "blocksZ": 2, "blockTiles": 3, "tileSize": 8, "seed": 5, "tiles": "town/kenney_city_builder"},
      "templates": {"cesium": {"gltf": "characters/CesiumMan.glb"}, "person": {"procedural": "seed-humanoid", "walkClip": "walk"},
                    "bird": {"procedural": "bird"}},
      "actors": [{"template": "person", "count": 12, "behaviour": "idle"}, {"template": "cesium", "count": 40, "behaviour": "walk"},
                 {"template": "bird", "count": 10, "behaviour": "flight", "area": {"center": [0, 0], "size": [40, 40]}},
                 {"template": "person", "count": 30, "behaviour": "walk"}],
      "effects": {"avoidance": true, "gaze": true, "face": true},
      "camera": {"fov": 60, "near": 0.2, "far": 500, "path": [{"time": 0, "eye": [0, 30, 50], "target": [0, 0, 0]}]}
    })";
}

}  // namespace

// A rank that draws nothing builds only what stepping the walkers needs (Scope::Walkers), on the
// navigation mesh rank 0 sent it: no crowd, no scene graph, no other behaviour, and its walkers,
// placed slot for slot as in the whole world, walk exactly as there.
TEST(SimulationScope, AWalkersWorldOnAnotherProcesssMeshWalksAsTheWholeWorld) {
    const std::string text = mixedTown();
    auto whole = sim::Simulation::build(sim::parseScene(text, testkit::sharedAssets()));
    const auto mesh = sim::NavMesh::fromBytes(whole->navMesh()->toBytes());  // as a rank receives it
    auto walkers = sim::Simulation::build(sim::parseScene(text, testkit::sharedAssets()), {},
                                          {sim::Simulation::Scope::Walkers, mesh});
    EXPECT_EQ(walkers->scope(), sim::Simulation::Scope::Walkers);
    EXPECT_EQ(walkers->crowd().size(), 0u);
    EXPECT_EQ(walkers->root().childCount(), 0u) << "no town, no group nodes";
    ASSERT_EQ(walkers->templates().size(), 2u) << "the walkers' templates only";
    for (const char* effect : {"idle", "flight", "gaze", "face"})
        EXPECT_EQ(walkers->effects().of(effect).constructed, 0u) << effect;
    ASSERT_NE(walkers->locomotion(), nullptr);
    const std::size_t n = whole->locomotion()->size();
    ASSERT_EQ(walkers->locomotion()->size(), n);
    for (int f = 0; f < 90; ++f) whole->step(), walkers->step();
    EXPECT_EQ(walkers->now().time, whole->now().time);
    double moved = 0.0;
    for (std::uint32_t slot = 0; slot < n; ++slot) {
        ASSERT_EQ(walkers->locomotion()->position(slot), whole->locomotion()->position(slot)) << "walker " << slot;
        ASSERT_EQ(walkers->locomotion()->speed(slot), whole->locomotion()->speed(slot)) << "walker " << slot;
        moved += walkers->locomotion()->speed(slot);
    }
    EXPECT_GT(moved / double(n), 0.5) << "they walk: the comparison proves something";
}

// A rank posing the walkers it steps builds every actor but not the town (Scope::Actors): its
// actors, groups, templates and draw numbers are the whole world's, the actors of groups that do
// not walk stand in, absent, and its walkers walk and are drawn as there.
TEST(SimulationScope, AnActorsWorldNumbersItsActorsAsTheWholeWorldAndDrawsItsWalkersAlike) {
    const std::string text = mixedTown();
    auto whole = sim::Simulation::build(sim::parseScene(text, testkit::sharedAssets()));
    const auto mesh = sim::NavMesh::fromBytes(whole->navMesh()->toBytes());
    auto actors = sim::Simulation::build(sim::parseScene(text, testkit::sharedAssets()), {}, {sim::Simulation::Scope::Actors, mesh});
    EXPECT_EQ(actors->scope(), sim::Simulation::Scope::Actors);
    ASSERT_EQ(actors->crowd().size(), whole->crowd().size());
    ASSERT_EQ(actors->groups().size(), whole->groups().size());
    for (std::size_t g = 0; g < whole->groups().size(); ++g) EXPECT_EQ(actors->groups()[g].actors, whole->groups()[g].actors) << "group " << g;
    ASSERT_EQ(actors->templates().size(), whole->templates().size());
    EXPECT_EQ(actors->root().childCount() + 1, whole->root().childCount()) << "every group node, no town";
    EXPECT_EQ(actors->effects().of("idle").constructed + actors->effects().of("flight").constructed, 0u) << "the others stand in";
    for (const char* effect : {"gaze", "face"}) EXPECT_GT(actors->effects().of(effect).constructed, 0u) << "the walkers' " << effect;
    ActorProcessor wholeProcessor(whole->crowd()), actorsProcessor(actors->crowd());
    const DrawReferences a = actorDrawReferences(whole->crowd(), whole->root(), wholeProcessor);
    const DrawReferences b = actorDrawReferences(actors->crowd(), actors->root(), actorsProcessor);
    EXPECT_EQ(a.nodeCount(), b.nodeCount());
    EXPECT_EQ(a.drawableCount(), b.drawableCount());
    for (std::uint32_t n = 0; n < a.drawableCount(); ++n) EXPECT_EQ(a.drawable(n)->name(), b.drawable(n)->name()) << "drawable " << n;
    // Stepped and drawn the same: the walkers' items are the whole world's, the others' none.
    const Camera camera = whole->camera().at(0.0, 16.0 / 9.0);
    std::vector<char> walks(whole->crowd().size(), 0);
    for (const auto& g : whole->groups())
        for (ActorId id : g.actors) walks[id] = g.behaviour == "walk";
    std::size_t walkerItems = 0;
    for (int f = 0; f < 20; ++f) {
        whole->step(), actors->step();
        wholeProcessor.processFrame(whole->root(), camera, whole->now().time);
        const ActorFrameStatistics& s = actorsProcessor.processFrame(actors->root(), camera, actors->now().time);
        EXPECT_EQ(s.actorsAbsent, 22u) << "the standing people and the birds";
        std::vector<const DrawItem*> expected;
        for (const DrawItem& item : wholeProcessor.drawList().items())
            if (item.actor != kNoActor && walks[item.actor]) expected.push_back(&item);
        std::size_t k = 0;
        for (const DrawItem& item : actorsProcessor.drawList().items()) {
            ASSERT_NE(item.actor, kNoActor) << "no town";
            ASSERT_LT(k, expected.size());
            EXPECT_EQ(item.actor, expected[k]->actor);
            EXPECT_TRUE(item.world == expected[k]->world) << "actor " << item.actor;
            ASSERT_EQ(item.skinPaletteSize, expected[k]->skinPaletteSize);
            for (std::uint32_t j = 0; j < item.skinPaletteSize; ++j) ASSERT_EQ(item.skinPalette[j], expected[k]->skinPalette[j]);
            ++k;
        }
        EXPECT_EQ(k, expected.size());
        walkerItems += k;
    }
    EXPECT_GT(walkerItems, 100u) << "walkers were drawn";
    // The stand-ins were never shown: their per-frame state was never written (no memory taken).
    EXPECT_EQ(actors->crowd().deferredStates(), 22u);
    EXPECT_EQ(whole->crowd().deferredStates(), 0u);
    // Rank 0 draws: it needs the whole world; a walkers' world cannot pose.
    sim::Ranks ranks;
    if (ranks.size() == 1) {
        EXPECT_THROW(actors->distribute(ranks, true), std::logic_error);
        auto stepping = sim::Simulation::build(sim::parseScene(text, testkit::sharedAssets()), {}, {sim::Simulation::Scope::Walkers, mesh});
        EXPECT_THROW(stepping->distribute(ranks, true), std::logic_error);
    }
}

// A mesh built for another scene (other settings) is refused, asking whether the ranks read the same
// file; rank 0 never builds for walkers only.
TEST(SimulationScope, AMeshOfAnotherSceneIsRefused) {
    const char* text = R"({"seed": 1, "walkways": {"floors": [{"center": [0, 0], "size": [20, 20]}], "cellSize": 0.2, "bodyRadius": 0.25},
      "templates": {"person": {"procedural": "seed-humanoid", "walkClip": "walk"}},
      "actors": [{"template": "person", "count": 4, "behaviour": "walk", "area": {"center": [0, 0], "size": [10, 10]}}]})";
    auto small = sim::Simulation::build(sim::parseScene(text, testkit::sharedAssets()));
    auto town = walkers();
    try {
        sim::Simulation::build(town->description(), {}, {sim::Simulation::Scope::Walkers, small->sharedNavMesh()});
        FAIL() << "another scene's mesh was taken";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("do all ranks read the same scene file?"), std::string::npos) << e.what();
    }
}
