// The town's layout: roads form a connected grid whose tiles, as turned, join exactly their road
// neighbours; buildings face a street; the same seed gives the same town.

#include <gtest/gtest.h>

#include <set>

#include "throng/sim/TownLayout.h"

using namespace throng::sim;

namespace {

// Road openings of a kind turned by q (+Z 1, +X 2, -Z 4, -X 8), from the models' geometry.
unsigned openings(TileKind kind, int q) {
    unsigned base = 0;
    switch (kind) {
        case TileKind::RoadStraight:
        case TileKind::RoadStraightLightposts: base = 1 | 4; break;
        case TileKind::RoadCorner: base = 8 | 1; break;
        case TileKind::RoadSplit: base = 8 | 2 | 1; break;
        case TileKind::RoadIntersection: base = 15; break;
        default: return 0;
    }
    for (int i = 0; i < q; ++i) base = ((base << 1) | (base >> 3)) & 15u;
    return base;
}

}  // namespace

TEST(TownLayout, RoadsJoinTheirNeighboursAndBuildingsFaceAStreet) {
    TownDescription d;
    d.blocksX = 4;
    d.blocksZ = 3;
    d.blockTiles = 3;
    d.seed = 11;
    const TownLayout t = layoutTown(d);
    ASSERT_EQ(t.tilesX, 4 * 4 + 1);
    ASSERT_EQ(t.tilesZ, 3 * 4 + 1);
    ASSERT_EQ(t.tiles.size(), std::size_t(t.tilesX * t.tilesZ));
    auto at = [&](int x, int z) -> const TilePlacement* {
        if (x < 0 || z < 0 || x >= t.tilesX || z >= t.tilesZ) return nullptr;
        return &t.tiles[std::size_t(z * t.tilesX + x)];
    };
    std::set<TileKind> kinds;
    int roads = 0, buildings = 0;
    for (const TilePlacement& p : t.tiles) {
        kinds.insert(p.kind);
        if (tileIsRoad(p.kind)) {
            ++roads;
            unsigned neighbours = 0;
            const int dx[4] = {0, 1, 0, -1}, dz[4] = {1, 0, -1, 0};
            for (int k = 0; k < 4; ++k)
                if (const TilePlacement* n = at(p.x + dx[k], p.z + dz[k]); n && tileIsRoad(n->kind)) neighbours |= 1u << k;
            const unsigned open = openings(p.kind, p.quarterTurns);
            if (__builtin_popcount(neighbours) >= 2) {
                EXPECT_EQ(open, neighbours) << "road at " << p.x << ", " << p.z;
            }
        } else if (!tileWalkable(p.kind) && p.kind != TileKind::GrassTrees && p.kind != TileKind::GrassTreesTall) {
            ++buildings;
            // The front (+Z turned) opens onto a road.
            const int dx[4] = {0, 1, 0, -1}, dz[4] = {1, 0, -1, 0};
            const TilePlacement* front = at(p.x + dx[p.quarterTurns], p.z + dz[p.quarterTurns]);
            ASSERT_NE(front, nullptr);
            EXPECT_TRUE(tileIsRoad(front->kind)) << "building at " << p.x << ", " << p.z;
        }
    }
    EXPECT_GT(roads, 80);
    EXPECT_GT(buildings, 20);
    EXPECT_TRUE(kinds.count(TileKind::RoadIntersection));
    EXPECT_TRUE(kinds.count(TileKind::RoadSplit));
    EXPECT_TRUE(kinds.count(TileKind::RoadCorner));
    // Reproducible from its seed, different with another.
    const TownLayout again = layoutTown(d);
    d.seed = 12;
    const TownLayout other = layoutTown(d);
    bool same = true, differs = false;
    for (std::size_t i = 0; i < t.tiles.size(); ++i) {
        same = same && t.tiles[i].kind == again.tiles[i].kind && t.tiles[i].quarterTurns == again.tiles[i].quarterTurns;
        differs = differs || t.tiles[i].kind != other.tiles[i].kind;
    }
    EXPECT_TRUE(same);
    EXPECT_TRUE(differs);
}
