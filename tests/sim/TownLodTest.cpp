// Town LOD built from the scene file: absent, the town holds no LOD node and nothing is simplified;
// declared, every tile model becomes an LOD node with one child per level, the coarser levels
// holding fewer triangles, and the CULL of a far camera draws fewer triangles than at full detail.

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "throng/testkit/Assets.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/LOD.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"

using namespace throng;

namespace {

std::unique_ptr<sim::Simulation> smallTown(const std::string& lod) {
    const std::string text = R"({
      "seed": 3,
      "town": {"blocksX": 2, "blocksZ": 2, "blockTiles": 3, "tileSize": 8, "seed": 5, "tiles": "town/kenney_city_builder")" +
                             lod + R"(},
      "templates": {"bird": {"procedural": "bird"}},
      "actors": [],
      "camera": {"fov": 60, "near": 0.2, "far": 1000, "path": [{"time": 0, "eye": [0, 150, 300], "target": [0, 0, 0]}]}
    })";
    return sim::Simulation::build(sim::parseScene(text, testkit::sharedAssets()));
}

// LOD nodes under `node`, and the triangles of the first and of the last child of each.
struct LodCount {
    int nodes = 0;
    std::uint64_t finest = 0, coarsest = 0;
};

void countLods(const Node& node, LodCount& c) {
    if (const auto* lod = dynamic_cast<const LOD*>(&node)) {
        ++c.nodes;
        ASSERT_GE(lod->childCount(), 2u);
        c.finest += dynamic_cast<const Geometry&>(lod->child(0)).drawable().primitiveCount();
        c.coarsest += dynamic_cast<const Geometry&>(lod->child(lod->childCount() - 1)).drawable().primitiveCount();
        return;
    }
    if (const auto* group = dynamic_cast<const Group*>(&node))
        for (std::size_t i = 0; i < group->childCount(); ++i) countLods(group->child(i), c);
}

std::uint64_t trianglesDrawn(sim::Simulation& world) {
    ActorProcessor processor(world.crowd());
    const Camera camera = world.camera().at(0.0, 16.0 / 9.0);
    processor.processFrame(world.root(), camera, world.step().time);
    return processor.drawList().primitiveCount();
}

}  // namespace

TEST(TownLod, AbsentBuildsNoLodNode) {
    auto world = smallTown("");
    LodCount c;
    countLods(world->root(), c);
    EXPECT_EQ(c.nodes, 0);
}

TEST(TownLod, DeclaredBuildsCoarserLevelsAndDrawsFewerTrianglesFarAway) {
    auto full = smallTown("");
    auto world = smallTown(R"(, "lod": [{"until": 50}, {"until": 100, "triangles": 0.5}, {"triangles": 0.25}])");
    LodCount c;
    countLods(world->root(), c);
    EXPECT_GT(c.nodes, 0);
    EXPECT_LT(double(c.coarsest), 0.5 * double(c.finest)) << "the last level keeps about a quarter of the triangles";
    const std::uint64_t a = trianglesDrawn(*full), b = trianglesDrawn(*world);
    EXPECT_GT(a, 0u);
    EXPECT_LT(double(b), 0.5 * double(a)) << "every tile is beyond 100 m from this camera";
}

// The scene's town/lodScale keeps declared levels unused (the full town drawn, as without LOD) until
// Simulation::setTownLodScale asks for them, whatever the actors' LOD scale.
TEST(TownLod, ASmallTownLodScaleDrawsTheFullTownUntilABudgetAsks) {
    auto full = smallTown("");
    auto world = smallTown(R"(, "lod": [{"until": 50}, {"until": 100, "triangles": 0.5}, {"triangles": 0.25}], "lodScale": 0.01)");
    EXPECT_TRUE(world->townHasLod());
    EXPECT_FALSE(full->townHasLod());
    EXPECT_EQ(world->townLodScale(), 0.01);
    EXPECT_EQ(trianglesDrawn(*world), trianglesDrawn(*full)) << "the levels built, none used";
    world->setTownLodScale(1.0);
    EXPECT_LT(double(trianglesDrawn(*world)), 0.5 * double(trianglesDrawn(*full))) << "asked for: the far levels";
    EXPECT_THROW(world->setTownLodScale(0.0), std::invalid_argument);
    EXPECT_THROW(world->setTownLodScale(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_EQ(world->townLodScale(), 1.0) << "a refused scale changes nothing";
}
