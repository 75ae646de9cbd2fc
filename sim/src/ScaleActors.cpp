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
