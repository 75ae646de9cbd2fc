#include "throng/sim/TownRegions.h"

#include "throng/sim/SceneError.h"

namespace throng::sim {

RegionGrid townRegions(const TownDescription& t, const std::string& file) {
    const int period = t.blockTiles + 1;
    const double block = period * t.tileSize;
    // The town's tiles are centred on the origin; the last road row and column lie past the last
    // block and belong to its region.
    const glm::dvec2 origin(-(t.blocksX * period + 1) * t.tileSize / 2.0, -(t.blocksZ * period + 1) * t.tileSize / 2.0);
    if (t.regions.empty()) {
        if (t.regionBlocks.x < 1 || t.regionBlocks.y < 1) throw SceneError(file, "/town/regions/size", "must be at least one block each way");
        return RegionGrid::tiled(origin, block, t.blocksX, t.blocksZ, t.regionBlocks.x, t.regionBlocks.y);
    }
    constexpr std::uint32_t kNone = ~0u;
    std::vector<std::uint32_t> cells(std::size_t(t.blocksX) * std::size_t(t.blocksZ), kNone);
    const auto str = [](glm::ivec2 v) { return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ")"; };
    for (std::size_t i = 0; i < t.regions.size(); ++i) {
        const RegionRectangle& r = t.regions[i];
        const std::string path = "/town/regions/" + std::to_string(i);
        if (r.from.x < 0 || r.from.y < 0 || r.to.x <= r.from.x || r.to.y <= r.from.y)
            throw SceneError(file, path, "must span at least one block: from " + str(r.from) + " to " + str(r.to) + " (blocks, 'to' excluded)");
        if (r.to.x > t.blocksX || r.to.y > t.blocksZ)
            throw SceneError(file, path + "/to", "reaches " + str(r.to) + ", beyond the town's " + std::to_string(t.blocksX) + " x " +
                                                      std::to_string(t.blocksZ) + " blocks");
        for (int z = r.from.y; z < r.to.y; ++z)
            for (int x = r.from.x; x < r.to.x; ++x) {
                std::uint32_t& c = cells[std::size_t(z) * t.blocksX + x];
                if (c != kNone)
                    throw SceneError(file, path, "overlaps region " + std::to_string(c) + " at block " + str({x, z}));
                c = std::uint32_t(i);
            }
    }
    for (int z = 0; z < t.blocksZ; ++z)
        for (int x = 0; x < t.blocksX; ++x)
            if (cells[std::size_t(z) * t.blocksX + x] == kNone)
                throw SceneError(file, "/town/regions", "do not cover the town: block " + str({x, z}) + " of " + std::to_string(t.blocksX) +
                                                            " x " + std::to_string(t.blocksZ) + " is in no region");
    return RegionGrid(origin, block, t.blocksX, t.blocksZ, std::move(cells));
}

}  // namespace throng::sim
