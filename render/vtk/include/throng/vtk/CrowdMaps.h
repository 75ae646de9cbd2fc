#pragma once
// Where a recorded crowd went and how fast: the positions of the frames a CrowdRecorder wrote,
// binned on the ground (x, z) into square cells, as VTK image data and as pictures.
//
//   DIR/crowd_maps.vti  point data per cell (at its centre): density (people per square metre, on
//                       average over the recorded frames), speed (mean m/s of those seen in it, 0
//                       where nobody was) and visits (actor-frames in it)
//   DIR/density.png     the density, dark blue (nobody) to red (the densest cell); a square of
//                       pixels per cell, at least 512 pixels on the longer side
//   DIR/speed.png       the mean speed, dark blue (still or nobody) to red (the 95th percentile of
//                       the cells someone was in, and faster)

#include <cstddef>
#include <filesystem>
#include <span>

namespace throng::vtk {

/// What the maps hold.
struct CrowdMapSummary {
    int cellsX = 0, cellsZ = 0;    ///< cells across and deep (0 when nothing was recorded)
    double cellSize = 0.0;         ///< metres
    double peakDensity = 0.0;      ///< people per square metre in the densest cell
    double peakSpeed = 0.0;        ///< m/s in the fastest cell
    std::size_t visits = 0;        ///< actor-frames binned
};

/// Bins `positions` (x y z per actor-frame, `frames` frames of them) with their `speeds` (one per
/// actor-frame) into cells of `cellSize` metres (larger if the ground would need more than 2048
/// cells a side) and writes crowd_maps.vti, density.png and speed.png into `directory`. Throws
/// std::invalid_argument for sizes that do not match or a cell size that is not positive, and
/// std::runtime_error naming a file that cannot be written. Nothing recorded: no file.
CrowdMapSummary writeCrowdMaps(const std::filesystem::path& directory, std::span<const double> positions,
                               std::span<const double> speeds, std::size_t frames, double cellSize = 4.0);

}  // namespace throng::vtk
