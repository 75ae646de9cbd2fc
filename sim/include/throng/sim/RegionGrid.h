#pragma once
// The fixed regions the world is divided into for stepping: a grid of equal cells on the ground
// (for the town, its city blocks), each cell belonging to exactly one region. A region is stepped
// by its own DetourCrowd, on its own thread when there are several; the layout comes from the scene
// and never from the number of threads, so the same layout gives the same trajectories whatever
// runs it. Points outside the grid belong to the region of the nearest cell.

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

namespace throng::sim {

/// Which region owns each cell of a grid on the ground (x, z).
class RegionGrid {
public:
    /// One region over everything.
    RegionGrid();
    /// A grid of `cellsX` x `cellsZ` cells of `cellSize` metres from `origin` (its -x, -z corner);
    /// `cellRegion[z * cellsX + x]` is the region of cell (x, z). Regions are numbered 0..n-1 and
    /// each must own a cell. Throws std::invalid_argument naming what is wrong.
    RegionGrid(glm::dvec2 origin, double cellSize, int cellsX, int cellsZ, std::vector<std::uint32_t> cellRegion);
    /// Regions of `spanX` x `spanZ` cells each (the last row and column may be smaller), numbered
    /// row by row. Throws std::invalid_argument if a size is not positive.
    static RegionGrid tiled(glm::dvec2 origin, double cellSize, int cellsX, int cellsZ, int spanX, int spanZ);

    /// Number of regions.
    std::uint32_t regionCount() const { return regions_; }
    /// The region owning the point (x, z).
    std::uint32_t regionOf(double x, double z) const;
    /// Regions other than `own` owning any point within `margin` metres (per axis) of (x, z),
    /// written to `out` in increasing order without repeats; returns how many (at most 8). The
    /// margin must be below the cell size.
    int regionsNear(double x, double z, double margin, std::uint32_t own, std::uint32_t out[8]) const;
    /// Each region's bounding rectangle on the ground (min x, min z, max x, max z), unbounded on the
    /// sides where it reaches the grid's edge (points beyond the grid belong to the edge cells).
    std::vector<glm::dvec4> regionBounds() const;
    /// Side of a cell, metres.
    double cellSize() const { return cellSize_; }
    /// Cells across.
    int cellsX() const { return cellsX_; }
    /// Cells deep.
    int cellsZ() const { return cellsZ_; }

private:
    glm::dvec2 origin_{0.0};
    double cellSize_ = 1.0;
    int cellsX_ = 1, cellsZ_ = 1;
    std::vector<std::uint32_t> cellRegion_{0};
    std::uint32_t regions_ = 1;
};

}  // namespace throng::sim
