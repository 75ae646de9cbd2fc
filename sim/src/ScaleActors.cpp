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
        if (std::int64_t(bx) * bz > kMaxTownBlocks) {
            const std::int64_t holds = std::int64_t(std::floor(perBlock * double(kMaxTownBlocks)));
            throw std::invalid_argument(
                "scaleActors: " + std::to_string(total) + " actors at the scene's density (" + std::to_string(int(std::lround(perBlock))) +
                " per city block) need a town of " + std::to_string(bx) + " x " + std::to_string(bz) +
                " blocks, but its navigation mesh is one Recast tile, which holds at most " + std::to_string(kMaxTownBlocks) +
                " blocks: this scene holds at most " + std::to_string(holds) + " actors (or declare a denser scene: more actors per block)");
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
