#include "throng/vtk/CrowdMaps.h"

#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "throng/scenegraph/WholeFile.h"

namespace throng::vtk {
namespace {

constexpr int kMaxCells = 2048;  // a side: the pictures stay a few MB at most

// `values` (one per cell, row z = 0 first) as an RGBA picture coloured over [0, peak], each cell a
// square of pixels so that a small town still makes a picture of at least 512 pixels a side.
void writePicture(const std::filesystem::path& file, const std::vector<double>& values, int nx, int nz, double peak) {
    auto colours = vtkSmartPointer<vtkLookupTable>::New();
    colours->SetHueRange(0.667, 0.0);  // blue to red
    colours->SetValueRange(0.35, 1.0);
    colours->SetTableRange(0.0, peak > 0.0 ? peak : 1.0);
    colours->Build();
    const int k = std::max(1, (512 + std::max(nx, nz) - 1) / std::max(nx, nz));
    auto rgba = vtkSmartPointer<vtkUnsignedCharArray>::New();
    rgba->SetNumberOfComponents(4);
    rgba->SetNumberOfTuples(vtkIdType(values.size()) * k * k);
    for (int y = 0; y < nz * k; ++y)
        for (int x = 0; x < nx * k; ++x)
            rgba->SetTypedTuple(vtkIdType(y) * nx * k + x, colours->MapValue(values[std::size_t(y / k) * std::size_t(nx) + std::size_t(x / k)]));
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(nx * k, nz * k, 1);
    image->GetPointData()->SetScalars(rgba);
    auto writer = vtkSmartPointer<vtkPNGWriter>::New();
    writer->SetFileName(file.c_str());
    writer->SetInputData(image);
    writer->Write();
    if (writer->GetErrorCode() != 0) throw std::runtime_error("writeCrowdMaps: cannot write " + file.string());
}

constexpr const char* kSpeedDensityHeader = "people,density_per_m2,actor_frames,share,mean_speed_m_s";
constexpr double kGroundBand = 1.0;  // metres above the lowest Reference Point still "on the ground"

// The fundamental diagram: every actor-frame on the ground counted with the people sharing its
// cell in that frame. `cellOf` gives each actor-frame's cell (the maps' grid). Writes
// speed_density.csv; returns the fullest cell's people in any frame.
int writeSpeedDensity(const std::filesystem::path& file, std::span<const double> positions, std::span<const double> speeds,
                      std::span<const std::size_t> frameSizes, const std::vector<std::size_t>& cellOf, std::size_t cells,
                      double cellSize) {
    double lowest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < speeds.size(); ++i) lowest = std::min(lowest, positions[3 * i + 1]);
    std::vector<std::uint32_t> inCell(cells, 0);  // this frame's people per cell; only touched cells reset
    std::vector<std::size_t> actorFrames;         // per count of people sharing the cell
    std::vector<double> speedSums;
    std::size_t onGround = 0;
    std::size_t first = 0;
    for (const std::size_t size : frameSizes) {
        const std::size_t end = first + size;
        auto ground = [&](std::size_t i) { return positions[3 * i + 1] <= lowest + kGroundBand; };
        for (std::size_t i = first; i < end; ++i)
            if (ground(i)) ++inCell[cellOf[i]];
        for (std::size_t i = first; i < end; ++i) {
            if (!ground(i)) continue;
            const std::uint32_t k = inCell[cellOf[i]];
            if (k >= actorFrames.size()) actorFrames.resize(k + 1, 0), speedSums.resize(k + 1, 0.0);
            ++actorFrames[k];
            speedSums[k] += speeds[i];
            ++onGround;
        }
        for (std::size_t i = first; i < end; ++i) inCell[cellOf[i]] = 0;
        first = end;
    }
    std::ostringstream out;
    out << kSpeedDensityHeader << '\n';
    char line[160];
    for (std::size_t k = 1; k < actorFrames.size(); ++k) {
        if (actorFrames[k] == 0) continue;
        std::snprintf(line, sizeof line, "%zu,%.9g,%zu,%.9g,%.9g\n", k, double(k) / (cellSize * cellSize), actorFrames[k],
                      double(actorFrames[k]) / double(onGround), speedSums[k] / double(actorFrames[k]));
        out << line;
    }
    try {
        writeWholeFile(file, out.str());
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string("writeCrowdMaps: ") + e.what());
    }
    return actorFrames.empty() ? 0 : int(actorFrames.size() - 1);
}

}  // namespace

std::vector<SpeedDensityRow> readSpeedDensity(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file.string() + ": cannot be read");
    std::string text;
    std::size_t lineNumber = 1;
    auto fail = [&](const std::string& why) { return std::runtime_error(file.string() + ":" + std::to_string(lineNumber) + ": " + why); };
    if (!std::getline(in, text) || text != kSpeedDensityHeader)
        throw fail("expected the header '" + std::string(kSpeedDensityHeader) + "'");
    std::vector<SpeedDensityRow> rows;
    while (std::getline(in, text)) {
        ++lineNumber;
        if (text.empty()) continue;
        std::vector<std::string> fields;
        std::stringstream line(text);
        for (std::string f; std::getline(line, f, ',');) fields.push_back(f);
        if (fields.size() != 5) throw fail(std::to_string(fields.size()) + " fields, not 5");
        double v[5];
        for (int c = 0; c < 5; ++c) {
            char* end = nullptr;
            v[c] = std::strtod(fields[std::size_t(c)].c_str(), &end);
            if (fields[std::size_t(c)].empty() || *end != '\0' || !std::isfinite(v[c]) || v[c] < 0.0)
                throw fail("field " + std::to_string(c + 1) + " ('" + fields[std::size_t(c)] + "') is not a number of at least 0");
        }
        SpeedDensityRow r{int(v[0]), v[1], std::size_t(v[2]), v[3], v[4]};
        if (double(r.people) != v[0] || r.people < 1 || double(r.actorFrames) != v[2] || r.share > 1.0)
            throw fail("people and actor-frames must be whole and positive, the share at most 1");
        if (!rows.empty() && r.people <= rows.back().people) throw fail("people must grow from line to line");
        rows.push_back(r);
    }
    return rows;
}

CrowdMapSummary writeCrowdMaps(const std::filesystem::path& directory, std::span<const double> positions,
                               std::span<const double> speeds, std::span<const std::size_t> frameSizes, double cellSize) {
    if (!(cellSize > 0.0) || !std::isfinite(cellSize))
        throw std::invalid_argument("writeCrowdMaps: the cell size must be positive, not " + std::to_string(cellSize));
    if (positions.size() % 3 != 0 || positions.size() / 3 != speeds.size())
        throw std::invalid_argument("writeCrowdMaps: " + std::to_string(positions.size()) + " coordinates for " +
                                    std::to_string(speeds.size()) + " speeds (3 per actor-frame)");
    const std::size_t framed = std::accumulate(frameSizes.begin(), frameSizes.end(), std::size_t{0});
    if (framed != speeds.size())
        throw std::invalid_argument("writeCrowdMaps: the frames hold " + std::to_string(framed) + " actor-frames, not the " +
                                    std::to_string(speeds.size()) + " given");
    CrowdMapSummary summary;
    const std::size_t n = speeds.size();
    const std::size_t frames = frameSizes.size();
    if (n == 0 || frames == 0) return summary;
    double x0 = std::numeric_limits<double>::infinity(), z0 = x0, x1 = -x0, z1 = -x0;
    for (std::size_t i = 0; i < n; ++i) {
        x0 = std::min(x0, positions[3 * i]), x1 = std::max(x1, positions[3 * i]);
        z0 = std::min(z0, positions[3 * i + 2]), z1 = std::max(z1, positions[3 * i + 2]);
    }
    const double side = std::max(x1 - x0, z1 - z0);
    cellSize = std::max(cellSize, side / (kMaxCells - 1));
    x0 = std::floor(x0 / cellSize) * cellSize, z0 = std::floor(z0 / cellSize) * cellSize;
    const int nx = int(std::floor((x1 - x0) / cellSize)) + 1, nz = int(std::floor((z1 - z0) / cellSize)) + 1;
    std::vector<double> visits(std::size_t(nx) * std::size_t(nz), 0.0), speed(visits.size(), 0.0), density(visits.size(), 0.0);
    std::vector<std::size_t> cellOf(n);
    for (std::size_t i = 0; i < n; ++i) {
        const int cx = std::min(nx - 1, int((positions[3 * i] - x0) / cellSize));
        const int cz = std::min(nz - 1, int((positions[3 * i + 2] - z0) / cellSize));
        const std::size_t c = std::size_t(cz) * std::size_t(nx) + std::size_t(cx);
        cellOf[i] = c;
        visits[c] += 1.0, speed[c] += speeds[i];
    }
    const double perVisit = 1.0 / (double(frames) * cellSize * cellSize);
    for (std::size_t c = 0; c < visits.size(); ++c) {
        density[c] = visits[c] * perVisit;
        if (visits[c] > 0.0) speed[c] /= visits[c];
        summary.peakDensity = std::max(summary.peakDensity, density[c]);
        summary.peakSpeed = std::max(summary.peakSpeed, speed[c]);
    }
    summary.cellsX = nx, summary.cellsZ = nz, summary.cellSize = cellSize, summary.visits = n;

    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(nx, nz, 1);
    image->SetOrigin(x0 + cellSize / 2.0, z0 + cellSize / 2.0, 0.0);  // image y is the ground's z
    image->SetSpacing(cellSize, cellSize, 1.0);
    for (const auto& [name, values] : {std::pair{"density", &density}, std::pair{"speed", &speed}, std::pair{"visits", &visits}}) {
        auto array = vtkSmartPointer<vtkDoubleArray>::New();
        array->SetName(name);
        array->SetNumberOfValues(vtkIdType(values->size()));
        for (std::size_t c = 0; c < values->size(); ++c) array->SetValue(vtkIdType(c), (*values)[c]);
        image->GetPointData()->AddArray(array);
    }
    const std::filesystem::path vti = directory / "crowd_maps.vti";
    auto writer = vtkSmartPointer<vtkXMLImageDataWriter>::New();
    writer->SetFileName(vti.c_str());
    writer->SetInputData(image);
    writer->SetDataModeToAppended();
    writer->SetCompressorTypeToZLib();
    if (writer->Write() == 0) throw std::runtime_error("writeCrowdMaps: cannot write " + vti.string());
    writePicture(directory / "density.png", density, nx, nz, summary.peakDensity);
    // Speeds coloured up to the 95th percentile of the cells someone was in: a few fast movers (a
    // flock overhead) would otherwise leave every walker's cell the same blue.
    std::vector<double> seen;
    for (std::size_t c = 0; c < visits.size(); ++c)
        if (visits[c] > 0.0) seen.push_back(speed[c]);
    std::nth_element(seen.begin(), seen.begin() + std::ptrdiff_t(seen.size() * 95 / 100), seen.end());
    writePicture(directory / "speed.png", speed, nx, nz, seen[seen.size() * 95 / 100]);
    const int fullest = writeSpeedDensity(directory / "speed_density.csv", positions, speeds, frameSizes, cellOf, visits.size(), cellSize);
    summary.peakLocalDensity = double(fullest) / (cellSize * cellSize);
    return summary;
}

}  // namespace throng::vtk
