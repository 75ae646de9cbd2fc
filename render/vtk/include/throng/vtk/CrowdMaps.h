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
//   DIR/speed_density.csv  the crowd's fundamental diagram: for the people on the ground, how many
//                       actor-frames were spent in a cell holding k people at that moment (a local
//                       density of k / cell area) and how fast they moved there (see SpeedDensityRow)

#include <cstddef>
#include <filesystem>
#include <span>
#include <vector>

namespace throng::vtk {

/// What the maps hold.
struct CrowdMapSummary {
    /// Cells across (x); the grid is cellsX by cellsZ (0 when nothing was recorded).
    int cellsX = 0, cellsZ = 0;    ///< cells across and deep (0 when nothing was recorded)
    double cellSize = 0.0;         ///< metres
    double peakDensity = 0.0;      ///< people per square metre in the densest cell
    double peakSpeed = 0.0;        ///< m/s in the fastest cell
    std::size_t visits = 0;        ///< actor-frames binned
    double peakLocalDensity = 0.0; ///< people per square metre in the fullest cell of any one frame
};

/// One line of speed_density.csv: the actor-frames of people on the ground (Reference Point within
/// a metre of the lowest recorded) spent in a cell that held `people` of them in that frame.
struct SpeedDensityRow {
    int people = 0;              ///< people in the cell at that moment (this one included)
    double density = 0.0;        ///< people / cell area, people per square metre
    std::size_t actorFrames = 0; ///< actor-frames spent in such cells
    double share = 0.0;          ///< their share of every actor-frame on the ground
    double meanSpeed = 0.0;      ///< their mean speed, m/s
};

/// Bins `positions` (x y z per actor-frame, frame after frame, `frameSizes[k]` actors in frame k)
/// with their `speeds` (one per actor-frame) into cells of `cellSize` metres (larger if the ground
/// would need more than 2048 cells a side) and writes crowd_maps.vti, density.png, speed.png and
/// speed_density.csv into `directory`. Throws std::invalid_argument for sizes that do not match or
/// a cell size that is not positive, and std::runtime_error naming a file that cannot be written.
/// Nothing recorded: no file.
CrowdMapSummary writeCrowdMaps(const std::filesystem::path& directory, std::span<const double> positions,
                               std::span<const double> speeds, std::span<const std::size_t> frameSizes, double cellSize = 4.0);

/// Reads a speed_density.csv written by writeCrowdMaps. Throws std::runtime_error naming the file
/// and line of anything else (a missing file, a bad header or number, rows out of order).
std::vector<SpeedDensityRow> readSpeedDensity(const std::filesystem::path& file);

}  // namespace throng::vtk
