#pragma once
// A town laid out procedurally from a seed and a size on a grid of modular tiles (the Kenney city
// builder set): a road every `blockTiles` tiles with straights, corners, T-junctions and crossings
// turned to connect; blocks of buildings facing the street behind pavement, and some parks.

#include <cstdint>
#include <string>
#include <vector>

#include "throng/sim/SceneDescription.h"

namespace throng::sim {

/// The kinds of tile.
enum class TileKind : std::uint8_t {
    RoadStraight, RoadStraightLightposts, RoadCorner, RoadSplit, RoadIntersection,
    Pavement, PavementFountain, Grass, GrassTrees, GrassTreesTall,
    BuildingSmallA, BuildingSmallB, BuildingSmallC, BuildingSmallD, BuildingGarage,
};
/// Number of tile kinds.
inline constexpr int kTileKindCount = 15;

/// The model file of a tile kind ("road-straight.glb", ...).
const char* tileFile(TileKind kind);
/// Whether people may walk on the tile (roads, pavement, grass).
bool tileWalkable(TileKind kind);
/// Whether it is a road tile.
bool tileIsRoad(TileKind kind);

/// One tile of the town.
struct TilePlacement {
    TileKind kind = TileKind::Grass;  ///< which model stands there
    int x = 0;           ///< column, from 0
    int z = 0;           ///< row, from 0
    int quarterTurns = 0;///< turns of 90 degrees about +Y (+Z goes to +X)
};

/// The laid-out town.
struct TownLayout {
    /// Tiles across (x); the grid is tilesX by tilesZ.
    int tilesX = 0, tilesZ = 0;     ///< grid size
    double tileSize = 8.0;          ///< metres per tile
    std::vector<TilePlacement> tiles;  ///< row by row

    /// World position of the centre of tile (x, z) (the town is centred on the origin).
    glm::dvec3 centre(int x, int z) const {
        return glm::dvec3((x + 0.5 - tilesX / 2.0) * tileSize, 0.0, (z + 0.5 - tilesZ / 2.0) * tileSize);
    }
    /// Side lengths of the town, metres.
    glm::dvec2 extent() const { return glm::dvec2(tilesX * tileSize, tilesZ * tileSize); }
};

/// Lays out the town `description` describes.
TownLayout layoutTown(const TownDescription& description);

}  // namespace throng::sim
