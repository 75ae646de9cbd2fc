// Resizing a scene: groups keep their proportions, the town grows to keep the scene's density, and
// a crowd no town can hold is refused before anything is built, saying what would fit.

#include <gtest/gtest.h>

#include "throng/sim/ScaleActors.h"

using namespace throng::sim;

namespace {

SceneDescription sixBySix() {
    SceneDescription s;
    s.town = TownDescription{};
    s.town->blocksX = s.town->blocksZ = 6;
    ActorGroupDescription walkers, idlers;
    walkers.count = 1500;
    walkers.area.center = glm::dvec2(10.0, -20.0);
    walkers.area.size = glm::dvec2(100.0, 50.0);
    idlers.count = 300;
    s.actors = {walkers, idlers};
    return s;  // 1800 actors on 36 blocks: 50 per block
}

}  // namespace

TEST(ScaleActors, TheTownGrowsWithTheCrowdAtTheScenesDensity) {
    SceneDescription s = sixBySix();
    scaleActors(s, 7200);  // four times the crowd: twice as many blocks each way
    EXPECT_EQ(s.actors[0].count + s.actors[1].count, 7200);
    EXPECT_EQ(s.actors[0].count, 6000);
    EXPECT_EQ(s.town->blocksX, 12);
    EXPECT_EQ(s.town->blocksZ, 12);
    EXPECT_EQ(s.actors[0].area.center, glm::dvec2(20.0, -40.0)) << "the groups' areas grow with the town";
    EXPECT_EQ(s.actors[0].area.size, glm::dvec2(200.0, 100.0));
    SceneDescription fewer = sixBySix();
    scaleActors(fewer, 100);
    EXPECT_EQ(fewer.town->blocksX, 6) << "a smaller crowd keeps the scene's town";
}

TEST(ScaleActors, ACrowdTheTownCannotHoldIsRefusedSayingWhyAndWhatFits) {
    SceneDescription s = sixBySix();
    std::string what;
    try {
        scaleActors(s, 2'000'000);
        FAIL() << "two million actors were accepted";
    } catch (const std::invalid_argument& e) {
        what = e.what();
    }
    EXPECT_NE(what.find("2000000 actors at the scene's density (50 per city block)"), std::string::npos) << what;
    EXPECT_NE(what.find("need a town of 200 x 200 blocks, 641601 tiles; a town holds at most 300000 tiles"), std::string::npos) << what;
    EXPECT_EQ(s.town->blocksX, 6) << "nothing changed";
    // The crowd it names fits.
    const std::string key = "this scene holds at most ";
    const std::size_t at = what.find(key);
    ASSERT_NE(at, std::string::npos) << what;
    const std::int64_t holds = std::stoll(what.substr(at + key.size()));
    EXPECT_GT(holds, 500'000);
    SceneDescription fits = sixBySix();
    EXPECT_NO_THROW(scaleActors(fits, holds));
    EXPECT_LE((fits.town->blocksX * 4 + 1) * (fits.town->blocksZ * 4 + 1), kMaxTownTiles);
}
