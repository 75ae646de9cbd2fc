#include "throng/sim/ScaleActors.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace throng::sim {

void scaleActors(SceneDescription& scene, std::int64_t total) {
    if (total < 0) throw std::invalid_argument("scaleActors: total must not be negative, got " + std::to_string(total));
    std::int64_t current = 0;
    for (const auto& g : scene.actors) current += g.count;
    if (current == 0) return;
    if (scene.town && total > current) {
        // The scene's density, kept: the town grows by the same factor both ways.
        TownDescription& town = *scene.town;
        const double blocks = double(town.blocksX) * double(town.blocksZ);
        const double perBlock = double(current) / blocks;
        const double grow = std::sqrt(double(total) / double(current));
        const int bx = int(std::ceil(town.blocksX * grow - 1e-9)), bz = int(std::ceil(town.blocksZ * grow - 1e-9));
        const std::int64_t side = town.blockTiles + 1;  // tiles per block, each way
        const auto tiles = [&](std::int64_t x, std::int64_t z) { return (x * side + 1) * (z * side + 1); };
        if (tiles(bx, bz) > kMaxTownTiles) {
            // The largest town of the scene's proportions within the limit, and the crowd it holds.
            double f = grow;
            while (f > 0.0 && tiles(std::int64_t(std::ceil(town.blocksX * f - 1e-9)), std::int64_t(std::ceil(town.blocksZ * f - 1e-9))) > kMaxTownTiles)
                f -= 0.01;
            const std::int64_t holds = std::int64_t(std::floor(double(current) * f * f));
            throw std::invalid_argument(
                "scaleActors: " + std::to_string(total) + " actors at the scene's density (" + std::to_string(int(std::lround(perBlock))) +
                " per city block) need a town of " + std::to_string(bx) + " x " + std::to_string(bz) + " blocks, " +
                std::to_string(tiles(bx, bz)) + " tiles; a town holds at most " + std::to_string(kMaxTownTiles) +
                " tiles: this scene holds at most " + std::to_string(holds) + " actors (or declare a denser scene: more actors per block)");
        }
        const double linear = double(bx) / double(town.blocksX);
        town.blocksX = bx;
        town.blocksZ = bz;
        for (auto& g : scene.actors) g.area.center *= linear, g.area.size *= linear;
    }
    std::vector<double> remainder;
    std::int64_t given = 0;
    for (auto& g : scene.actors) {
        const double exact = double(g.count) * double(total) / double(current);
        g.count = std::int64_t(std::floor(exact));
        given += g.count;
        remainder.push_back(exact - double(g.count));
    }
    while (given < total) {
        const auto i = std::size_t(std::max_element(remainder.begin(), remainder.end()) - remainder.begin());
        ++scene.actors[i].count;
        remainder[i] = -1.0;
        ++given;
    }
}

}  // namespace throng::sim
