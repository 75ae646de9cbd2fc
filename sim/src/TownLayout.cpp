#include "throng/sim/TownLayout.h"

#include <array>
#include <tuple>

#include "throng/sim/CounterRng.h"

namespace throng::sim {
namespace {

// Road connections of a tile as a bit set: +Z 1, +X 2, -Z 4, -X 8. Turning a tile a quarter about
// +Y takes +Z to +X, +X to -Z and so on: each bit moves one place up.
constexpr unsigned kPosZ = 1, kPosX = 2, kNegZ = 4, kNegX = 8;
unsigned turned(unsigned mask, int quarterTurns) {
    for (int q = 0; q < (quarterTurns & 3); ++q) mask = ((mask << 1) | (mask >> 3)) & 15u;
    return mask;
}

// The kind and turn joining exactly the roads in `mask`. The models join: straight +-Z, corner -X
// and +Z, split -X, +X and +Z, crossing all four.
std::pair<TileKind, int> roadFor(unsigned mask) {
    const std::array<std::pair<TileKind, unsigned>, 4> shapes = {
        {{TileKind::RoadStraight, kPosZ | kNegZ}, {TileKind::RoadCorner, kNegX | kPosZ},
         {TileKind::RoadSplit, kNegX | kPosX | kPosZ}, {TileKind::RoadIntersection, 15u}}};
    for (const auto& [kind, base] : shapes)
        for (int q = 0; q < 4; ++q)
            if (turned(base, q) == mask) return {kind, q};
    // A dead end (or a lone tile): a straight along the one neighbour.
    return {TileKind::RoadStraight, (mask & (kPosX | kNegX)) ? 1 : 0};
}

}  // namespace

const char* tileFile(TileKind kind) {
    static const char* files[kTileKindCount] = {
        "road-straight.glb", "road-straight-lightposts.glb", "road-corner.glb", "road-split.glb", "road-intersection.glb",
        "pavement.glb", "pavement-fountain.glb", "grass.glb", "grass-trees.glb", "grass-trees-tall.glb",
        "building-small-a.glb", "building-small-b.glb", "building-small-c.glb", "building-small-d.glb", "building-garage.glb"};
    return files[static_cast<int>(kind)];
}

bool tileIsRoad(TileKind kind) { return static_cast<int>(kind) <= static_cast<int>(TileKind::RoadIntersection); }

bool tileWalkable(TileKind kind) {
    switch (kind) {
        case TileKind::GrassTrees:
        case TileKind::GrassTreesTall:
        case TileKind::BuildingSmallA:
        case TileKind::BuildingSmallB:
        case TileKind::BuildingSmallC:
        case TileKind::BuildingSmallD:
        case TileKind::BuildingGarage: return false;
        default: return true;
    }
}

TownLayout layoutTown(const TownDescription& d) {
    TownLayout town;
    const int period = d.blockTiles + 1;  // a road, then a block
    town.tilesX = d.blocksX * period + 1;
    town.tilesZ = d.blocksZ * period + 1;
    town.tileSize = d.tileSize;
    const CounterRng rng(d.seed, 0x70776e);
    auto road = [&](int x, int z) {
        return x >= 0 && z >= 0 && x < town.tilesX && z < town.tilesZ && (x % period == 0 || z % period == 0);
    };
    for (int z = 0; z < town.tilesZ; ++z)
        for (int x = 0; x < town.tilesX; ++x) {
            TilePlacement t;
            t.x = x;
            t.z = z;
            const std::uint64_t cell = std::uint64_t(z) * 65536u + std::uint64_t(x);
            if (road(x, z)) {
                const unsigned mask = (road(x, z + 1) ? kPosZ : 0) | (road(x + 1, z) ? kPosX : 0) |
                                      (road(x, z - 1) ? kNegZ : 0) | (road(x - 1, z) ? kNegX : 0);
                std::tie(t.kind, t.quarterTurns) = roadFor(mask);
                if (t.kind == TileKind::RoadStraight && rng.uniform(cell) < 0.3) t.kind = TileKind::RoadStraightLightposts;
            } else {
                // Inside a block: which block, and where in it.
                const int bx = x / period, bz = z / period, lx = x % period, lz = z % period;
                const bool park = rng.uniform(std::uint64_t(bz) * 4096u + std::uint64_t(bx) + 7'000'000u) < 0.2;
                const bool edge = lx == 1 || lz == 1 || lx == d.blockTiles || lz == d.blockTiles;
                const double r = rng.uniform(cell + 1'000'000u);
                if (park) {
                    t.kind = r < 0.15 ? TileKind::PavementFountain : r < 0.45 ? TileKind::GrassTrees : r < 0.6 ? TileKind::GrassTreesTall : TileKind::Grass;
                } else if (edge && r < 0.8) {
                    const TileKind buildings[] = {TileKind::BuildingSmallA, TileKind::BuildingSmallB, TileKind::BuildingSmallC,
                                                  TileKind::BuildingSmallD, TileKind::BuildingGarage};
                    t.kind = buildings[rng.below(cell + 2'000'000u, 5)];
                    // Face the street: the models' fronts face +Z.
                    t.quarterTurns = lz == d.blockTiles ? 0 : lx == d.blockTiles ? 1 : lz == 1 ? 2 : 3;
                } else {
                    t.kind = TileKind::Pavement;
                }
            }
            town.tiles.push_back(t);
        }
    return town;
}

}  // namespace throng::sim
