#pragma once
// Conservative occluder boxes fitted inside static geometry, built once at load. An occluder must lie
// inside the opaque solid it stands for: from any eye outside the geometry, wherever the box is seen
// a front face of the real geometry is in front of it, so rejecting what a box hides never hides
// something visible.

#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "throng/scenegraph/AxisBox.h"
#include "throng/scenegraph/MeshData.h"

namespace throng {

/// Knobs of fitOccluderBoxes. Each is checked: a bad value throws std::invalid_argument naming it.
struct OccluderFitOptions {
    /// Voxels along the longest side of the meshes' bounding box (2..160); the other sides get as
    /// many near-cubic cells as fit. Finer finds more of the solid and costs O(resolution^4).
    int resolution = 48;
    /// At most this many boxes (1..64). Town buildings need more than a few: 16 found a third more
    /// hidden actors than 4 in the street (bench_frame --sections visibility).
    int maxBoxes = 16;
    /// A box after the first is kept only if it covers at least this share of the first box's
    /// volume in solid cells no earlier box covers (0..1).
    double minGain = 0.02;
    /// Every face of a box moves inwards by this fraction of a cell's edge along its axis
    /// (0.001..0.5): slack for the rasteriser's rounding and for triangles that graze a cell.
    double margin = 0.05;
};

/// What a fit found, for reports and tests.
struct OccluderFitStatistics {
    glm::ivec3 cells{0};          ///< voxel grid size along x, y, z (zero when nothing was voxelised)
    glm::vec3 cellSize{0.0f};     ///< edge of one cell along x, y, z (mesh units)
    std::size_t solidCells = 0;   ///< cells found entirely inside the solid
    std::size_t surfaceCells = 0; ///< cells a triangle passes through
    double boundsVolume = 0.0;    ///< volume of the meshes' bounding box
    double solidVolume = 0.0;     ///< volume of the solid cells
    double boxVolume = 0.0;       ///< volume of the returned boxes (overlaps counted once per box)
};

/// Axis-aligned boxes, in the meshes' own frame, lying inside the solid the meshes enclose together
/// (e.g. the primitives of one glTF tile), largest first. A cell of a voxel grid over the meshes'
/// bounding box counts as solid when no triangle passes through it and, along each of the six axis
/// directions, a triangle facing that direction (counter-clockwise seen from there) lies beyond it
/// over its whole footprint, so that an eye far that way sees a front face first; free cells joined
/// through faces no triangle lies on must all agree, so a pocket open to the outside is dropped
/// whole. Boxes are then taken greedily over solid cells (largest-volume box first, then the largest
/// over uncovered cells, grown through solid ones). Open or empty geometry yields no box.
/// Throws std::invalid_argument for bad options, a null mesh, non-finite positions or indices out
/// of range (naming the mesh's position in `meshes` and the offending vertex or index).
std::vector<AxisBox> fitOccluderBoxes(std::span<const MeshData* const> meshes, const OccluderFitOptions& options = {},
                                      OccluderFitStatistics* statistics = nullptr);

}  // namespace throng
