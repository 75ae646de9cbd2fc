#include "throng/sim/RegionGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace throng::sim {

RegionGrid::RegionGrid() = default;

RegionGrid::RegionGrid(glm::dvec2 origin, double cellSize, int cellsX, int cellsZ, std::vector<std::uint32_t> cellRegion)
    : origin_(origin), cellSize_(cellSize), cellsX_(cellsX), cellsZ_(cellsZ), cellRegion_(std::move(cellRegion)) {
    const std::string where = "RegionGrid: ";
    if (!(cellSize > 0.0) || !std::isfinite(cellSize)) throw std::invalid_argument(where + "argument 'cellSize' must be positive");
    if (cellsX < 1 || cellsZ < 1) throw std::invalid_argument(where + "the grid needs at least one cell each way");
    if (cellRegion_.size() != std::size_t(cellsX) * std::size_t(cellsZ))
        throw std::invalid_argument(where + std::to_string(cellRegion_.size()) + " cell regions for " + std::to_string(cellsX) + " x " +
                                    std::to_string(cellsZ) + " cells");
    regions_ = *std::max_element(cellRegion_.begin(), cellRegion_.end()) + 1;
    std::vector<char> used(regions_, 0);
    for (std::uint32_t r : cellRegion_) used[r] = 1;
    for (std::uint32_t r = 0; r < regions_; ++r)
        if (!used[r]) throw std::invalid_argument(where + "region " + std::to_string(r) + " owns no cell");
}

RegionGrid RegionGrid::tiled(glm::dvec2 origin, double cellSize, int cellsX, int cellsZ, int spanX, int spanZ) {
    if (spanX < 1 || spanZ < 1) throw std::invalid_argument("RegionGrid::tiled: region sizes must be positive");
    if (cellsX < 1 || cellsZ < 1) throw std::invalid_argument("RegionGrid::tiled: the grid needs at least one cell each way");
    const int across = (cellsX + spanX - 1) / spanX;
    std::vector<std::uint32_t> cells(std::size_t(cellsX) * std::size_t(cellsZ));
    for (int z = 0; z < cellsZ; ++z)
        for (int x = 0; x < cellsX; ++x) cells[std::size_t(z) * cellsX + x] = std::uint32_t((z / spanZ) * across + x / spanX);
    return RegionGrid(origin, cellSize, cellsX, cellsZ, std::move(cells));
}

std::uint32_t RegionGrid::regionOf(double x, double z) const {
    const int cx = std::clamp(int(std::floor((x - origin_.x) / cellSize_)), 0, cellsX_ - 1);
    const int cz = std::clamp(int(std::floor((z - origin_.y) / cellSize_)), 0, cellsZ_ - 1);
    return cellRegion_[std::size_t(cz) * cellsX_ + cx];
}

std::vector<glm::dvec4> RegionGrid::regionBounds() const {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<glm::dvec4> bounds(regions_, glm::dvec4(kInf, kInf, -kInf, -kInf));
    for (int cz = 0; cz < cellsZ_; ++cz)
        for (int cx = 0; cx < cellsX_; ++cx) {
            glm::dvec4& b = bounds[cellRegion_[std::size_t(cz) * cellsX_ + cx]];
            const double x0 = cx == 0 ? -kInf : origin_.x + cx * cellSize_, z0 = cz == 0 ? -kInf : origin_.y + cz * cellSize_;
            const double x1 = cx == cellsX_ - 1 ? kInf : origin_.x + (cx + 1) * cellSize_;
            const double z1 = cz == cellsZ_ - 1 ? kInf : origin_.y + (cz + 1) * cellSize_;
            b = glm::dvec4(std::min(b.x, x0), std::min(b.y, z0), std::max(b.z, x1), std::max(b.w, z1));
        }
    return bounds;
}

int RegionGrid::regionsNear(double x, double z, double margin, std::uint32_t own, std::uint32_t out[8]) const {
    int n = 0;
    if (regions_ == 1) return 0;
    // A margin below a cell: the eight probes reach every cell the square touches.
    for (int dz = -1; dz <= 1; ++dz)
        for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dz == 0) continue;
            const std::uint32_t r = regionOf(x + dx * margin, z + dz * margin);
            if (r == own || std::find(out, out + n, r) != out + n) continue;
            out[n++] = r;
        }
    std::sort(out, out + n);
    return n;
}

}  // namespace throng::sim
