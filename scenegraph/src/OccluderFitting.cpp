#include "throng/scenegraph/OccluderFitting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/vec3.hpp>

namespace throng {
namespace {

using DVec3 = glm::dvec3;

// A triangle may enter a cell by this fraction of the cell's edge and the cell still counts as free:
// faces lying on cell boundaries (walls on the bounding box) must not spoil the cells beside them.
// The margin (at least 0.001 of a cell) keeps boxes clear of such grazing triangles.
constexpr double kGraze = 1e-4;
// The columns that test a cell's corners stand this fraction of a cell inside it (below the smallest
// margin, so the untested sliver lies outside every box's outer faces).
constexpr double kColumnInset = 1e-3;

struct Triangle {
    DVec3 v[3];
};

[[noreturn]] void badOption(const std::string& name, const std::string& why) {
    throw std::invalid_argument("fitOccluderBoxes: option " + name + " " + why);
}

void checkOptions(const OccluderFitOptions& o) {
    if (o.resolution < 2 || o.resolution > 160) badOption("resolution", "must be in 2..160, got " + std::to_string(o.resolution));
    if (o.maxBoxes < 1 || o.maxBoxes > 64) badOption("maxBoxes", "must be in 1..64, got " + std::to_string(o.maxBoxes));
    if (!(o.minGain >= 0.0 && o.minGain <= 1.0)) badOption("minGain", "must be in 0..1, got " + std::to_string(o.minGain));
    if (!(o.margin >= 0.001 && o.margin <= 0.5)) badOption("margin", "must be in 0.001..0.5 (a fraction of a cell), got " + std::to_string(o.margin));
}

std::string meshLabel(std::size_t m, const MeshData& mesh) {
    return "fitOccluderBoxes: mesh " + std::to_string(m) + (mesh.name.empty() ? std::string() : " ('" + mesh.name + "')");
}

// Every triangle of every mesh in double precision, after checking what the fit relies on.
std::vector<Triangle> gatherTriangles(std::span<const MeshData* const> meshes) {
    std::vector<Triangle> tris;
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        if (!meshes[m]) throw std::invalid_argument("fitOccluderBoxes: mesh " + std::to_string(m) + " is null");
        const MeshData& mesh = *meshes[m];
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            const glm::vec3& p = mesh.positions[i];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw std::invalid_argument(meshLabel(m, mesh) + ": position of vertex " + std::to_string(i) + " is not finite");
        }
        if (mesh.indices.size() % 3 != 0)
            throw std::invalid_argument(meshLabel(m, mesh) + ": " + std::to_string(mesh.indices.size()) + " indices, not a multiple of 3");
        for (std::size_t i = 0; i < mesh.indices.size(); ++i)
            if (mesh.indices[i] >= mesh.positions.size())
                throw std::invalid_argument(meshLabel(m, mesh) + ": index " + std::to_string(i) + " refers to vertex " + std::to_string(mesh.indices[i]) +
                                            " of " + std::to_string(mesh.positions.size()));
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
            tris.push_back({{DVec3(mesh.positions[mesh.indices[i]]), DVec3(mesh.positions[mesh.indices[i + 1]]), DVec3(mesh.positions[mesh.indices[i + 2]])}});
    }
    return tris;
}

// The voxel grid over the bounding box: cells of equal size along each axis, planes exactly on it.
struct Grid {
    DVec3 lo{0.0}, hi{0.0}, cell{0.0};
    glm::ivec3 n{0};

    std::size_t count() const { return std::size_t(n.x) * std::size_t(n.y) * std::size_t(n.z); }
    std::size_t index(int x, int y, int z) const { return std::size_t(x) + std::size_t(n.x) * (std::size_t(y) + std::size_t(n.y) * std::size_t(z)); }
    // Coordinate of plane i along axis a; the last plane is the bounding box itself, not a sum.
    double plane(int a, int i) const { return i >= n[a] ? hi[a] : lo[a] + (hi[a] - lo[a]) * double(i) / double(n[a]); }
    double centre(int a, int i) const { return 0.5 * (plane(a, i) + plane(a, i + 1)); }
    // Range of cells whose closed extent may meet [a0, a1] along axis a.
    void span(int a, double a0, double a1, int& i0, int& i1) const {
        i0 = std::clamp(int(std::floor((a0 - lo[a]) / cell[a])) - 1, 0, n[a] - 1);
        i1 = std::clamp(int(std::floor((a1 - lo[a]) / cell[a])) + 1, 0, n[a] - 1);
    }
};

// Separating-axis test of a triangle against a box (centre c, half extents e); touching counts.
bool triangleOverlapsBox(const Triangle& t, const DVec3& c, const DVec3& e) {
    const DVec3 v0 = t.v[0] - c, v1 = t.v[1] - c, v2 = t.v[2] - c;
    for (int a = 0; a < 3; ++a) {
        if (std::min({v0[a], v1[a], v2[a]}) > e[a] || std::max({v0[a], v1[a], v2[a]}) < -e[a]) return false;
    }
    const DVec3 f[3] = {v1 - v0, v2 - v1, v0 - v2};
    for (int a = 0; a < 3; ++a) {
        DVec3 unit(0.0);
        unit[a] = 1.0;
        for (const DVec3& edge : f) {
            const DVec3 axis = glm::cross(unit, edge);
            const double p0 = glm::dot(v0, axis), p1 = glm::dot(v1, axis), p2 = glm::dot(v2, axis);
            const double r = e.x * std::abs(axis.x) + e.y * std::abs(axis.y) + e.z * std::abs(axis.z);
            if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
        }
    }
    const DVec3 normal = glm::cross(f[0], f[1]);
    const double d = glm::dot(normal, v0);
    const double r = e.x * std::abs(normal.x) + e.y * std::abs(normal.y) + e.z * std::abs(normal.z);
    return std::abs(d) <= r;
}

// What the triangles do to the grid: the cells they pass through (deeper than the graze allowance)
// and the faces between cells they lie on (within the allowance), which separate the cells beside.
struct SurfaceMarks {
    std::vector<std::uint8_t> cell;      // a triangle passes through the cell
    std::vector<std::uint8_t> face[3];   // a triangle lies on the face between a cell and its +axis neighbour
};

SurfaceMarks markSurface(const Grid& g, const std::vector<Triangle>& tris) {
    SurfaceMarks marks;
    marks.cell.assign(g.count(), 0);
    for (auto& f : marks.face) f.assign(g.count(), 0);
    const DVec3 half = 0.5 * g.cell * (1.0 - 2.0 * kGraze);
    for (const Triangle& t : tris) {
        const DVec3 tmin = glm::min(t.v[0], glm::min(t.v[1], t.v[2]));
        const DVec3 tmax = glm::max(t.v[0], glm::max(t.v[1], t.v[2]));
        int r0[3], r1[3];
        for (int a = 0; a < 3; ++a) g.span(a, tmin[a], tmax[a], r0[a], r1[a]);
        for (int z = r0[2]; z <= r1[2]; ++z)
            for (int y = r0[1]; y <= r1[1]; ++y)
                for (int x = r0[0]; x <= r1[0]; ++x) {
                    const std::size_t i = g.index(x, y, z);
                    const int at[3] = {x, y, z};
                    const DVec3 c(g.centre(0, x), g.centre(1, y), g.centre(2, z));
                    if (!marks.cell[i] && triangleOverlapsBox(t, c, half)) marks.cell[i] = 1;
                    for (int a = 0; a < 3; ++a) {
                        if (marks.face[a][i] || at[a] + 1 >= g.n[a]) continue;
                        // The face as a thin slab, narrowed so that walls meeting it at an edge do not count.
                        DVec3 fc = c, fh = half;
                        fc[a] = g.plane(a, at[a] + 1);
                        fh[a] = kGraze * g.cell[a];
                        if (triangleOverlapsBox(t, fc, fh)) marks.face[a][i] = 1;
                    }
                }
    }
    return marks;
}

// For each cell, whether along each of the six axis directions a triangle facing that direction lies
// beyond the cell: seen from far away along that direction, the renderer draws that face in front of
// the cell. Tested on nine columns per cell (near its corners, its edge middles, its centre) so that
// an overhang ending above part of a cell does not count for all of it; the corner columns stand
// kColumnInset of a cell inside, so that a wall on a cell's side does not hide the roof edge it meets
// from them. Columns meet triangles by the rasteriser's top-left rule, so a column through a shared
// edge or vertex hits exactly one triangle.
std::vector<std::uint8_t> enclosedCells(const Grid& g, const std::vector<Triangle>& tris) {
    std::vector<std::uint8_t> enclosed(g.count(), 1);
    constexpr double kInf = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        // Three columns per cell along b and along c: just inside its low side, at its centre, just
        // inside its high side.
        const int mb = 3 * g.n[b], mc = 3 * g.n[c];
        auto sample = [&](int axis, int t) {
            const int cell = t / 3, at = t % 3;
            return at == 1 ? g.centre(axis, cell) : at == 0 ? g.plane(axis, cell) + kColumnInset * g.cell[axis] : g.plane(axis, cell + 1) - kColumnInset * g.cell[axis];
        };
        // Per column: the farthest face towards +a that faces +a, and towards -a that faces -a.
        std::vector<double> topUp(std::size_t(mb) * std::size_t(mc), -kInf), bottomDown(std::size_t(mb) * std::size_t(mc), kInf);
        for (const Triangle& t : tris) {
            // Projected onto (b, c) the signed area equals the normal's component along a.
            DVec3 p[3] = {t.v[0], t.v[1], t.v[2]};
            const double area = (p[1][b] - p[0][b]) * (p[2][c] - p[0][c]) - (p[1][c] - p[0][c]) * (p[2][b] - p[0][b]);
            if (area == 0.0 || !std::isfinite(area)) continue;
            const bool facesUp = area > 0.0;
            if (!facesUp) std::swap(p[1], p[2]);
            int j0, j1, k0, k1;
            g.span(b, std::min({p[0][b], p[1][b], p[2][b]}), std::max({p[0][b], p[1][b], p[2][b]}), j0, j1);
            g.span(c, std::min({p[0][c], p[1][c], p[2][c]}), std::max({p[0][c], p[1][c], p[2][c]}), k0, k1);
            for (int tc = 3 * k0; tc <= 3 * k1 + 2; ++tc) {
                const double qc = sample(c, tc);
                for (int tb = 3 * j0; tb <= 3 * j1 + 2; ++tb) {
                    const double qb = sample(b, tb);
                    double w[3];
                    bool inside = true;
                    for (int e = 0; e < 3 && inside; ++e) {
                        const DVec3& from = p[(e + 1) % 3];
                        const DVec3& to = p[(e + 2) % 3];
                        const double db = to[b] - from[b], dc = to[c] - from[c];
                        // Evaluated from the edge's lexicographically first end, so that the two
                        // triangles sharing it get exactly opposite values (no rounding gap).
                        const bool flip = to[b] < from[b] || (to[b] == from[b] && to[c] < from[c]);
                        const DVec3& origin = flip ? to : from;
                        const double eb = flip ? -db : db, ec = flip ? -dc : dc;
                        const double canonical = eb * (qc - origin[c]) - ec * (qb - origin[b]);
                        w[e] = flip ? -canonical : canonical;
                        // Top-left rule: an edge shared by two triangles is claimed by exactly one.
                        inside = w[e] > 0.0 || (w[e] == 0.0 && (dc > 0.0 || (dc == 0.0 && db < 0.0)));
                    }
                    if (!inside) continue;
                    const double sum = w[0] + w[1] + w[2];
                    if (!(sum > 0.0)) continue;
                    const double depth = (w[0] * p[0][a] + w[1] * p[1][a] + w[2] * p[2][a]) / sum;
                    const std::size_t column = std::size_t(tb) + std::size_t(mb) * std::size_t(tc);
                    if (facesUp) topUp[column] = std::max(topUp[column], depth);
                    else bottomDown[column] = std::min(bottomDown[column], depth);
                }
            }
        }
        // A cell is covered towards +a when every one of its nine columns has such a face beyond
        // its centre (a free cell has no face inside it, so beyond the centre is beyond the cell).
        for (int k = 0; k < g.n[c]; ++k)
            for (int j = 0; j < g.n[b]; ++j) {
                double nearestUp = kInf, nearestDown = -kInf;
                for (int dk = 0; dk <= 2; ++dk)
                    for (int dj = 0; dj <= 2; ++dj) {
                        const std::size_t column = std::size_t(3 * j + dj) + std::size_t(mb) * std::size_t(3 * k + dk);
                        nearestUp = std::min(nearestUp, topUp[column]);
                        nearestDown = std::max(nearestDown, bottomDown[column]);
                    }
                for (int i = 0; i < g.n[a]; ++i) {
                    const double centre = g.centre(a, i);
                    if (nearestUp > centre && nearestDown < centre) continue;
                    int cell[3];
                    cell[a] = i;
                    cell[b] = j;
                    cell[c] = k;
                    enclosed[g.index(cell[0], cell[1], cell[2])] = 0;
                }
            }
    }
    return enclosed;
}

// Free cells that are enclosed, keeping only groups of free cells joined through faces no triangle
// lies on that all are: such cells are inside or outside together on a closed surface, so a group
// that disagrees shows an opening and is dropped whole.
std::vector<std::uint8_t> solidCells(const Grid& g, const SurfaceMarks& marks, const std::vector<std::uint8_t>& enclosed) {
    const std::vector<std::uint8_t>& surface = marks.cell;
    std::vector<std::uint8_t> solid(g.count(), 0);
    std::vector<std::uint8_t> seen(g.count(), 0);
    std::vector<std::size_t> group, stack;
    for (std::size_t start = 0; start < g.count(); ++start) {
        if (surface[start] || seen[start]) continue;
        group.clear();
        stack.assign(1, start);
        seen[start] = 1;
        bool allEnclosed = true;
        while (!stack.empty()) {
            const std::size_t i = stack.back();
            stack.pop_back();
            group.push_back(i);
            allEnclosed = allEnclosed && enclosed[i];
            const int x = int(i % std::size_t(g.n.x)), y = int((i / std::size_t(g.n.x)) % std::size_t(g.n.y)), z = int(i / (std::size_t(g.n.x) * std::size_t(g.n.y)));
            for (int a = 0; a < 3; ++a)
                for (int step = -1; step <= 1; step += 2) {
                    int q[3] = {x, y, z};
                    q[a] += step;
                    if (q[a] < 0 || q[a] >= g.n[a]) continue;
                    const std::size_t j = g.index(q[0], q[1], q[2]);
                    if (surface[j] || seen[j] || marks.face[a][step > 0 ? i : j]) continue;
                    seen[j] = 1;
                    stack.push_back(j);
                }
        }
        if (allEnclosed)
            for (std::size_t i : group) solid[i] = 1;
    }
    return solid;
}

// A box of cells, inclusive ranges.
struct CellBox {
    glm::ivec3 lo{0}, hi{-1};
    std::size_t cells() const {
        const glm::ivec3 s = hi - lo + 1;
        return s.x > 0 && s.y > 0 && s.z > 0 ? std::size_t(s.x) * std::size_t(s.y) * std::size_t(s.z) : 0;
    }
};

// The box of most cells all set in `mask`: for every range of y layers, the largest rectangle of
// (x, z) columns set throughout the range, by the histogram-and-stack algorithm. O(ny^2 nx nz).
CellBox largestBox(const Grid& g, const std::vector<std::uint8_t>& mask) {
    CellBox best;
    std::size_t bestCells = 0;
    const int nx = g.n.x, ny = g.n.y, nz = g.n.z;
    std::vector<std::uint8_t> columns(std::size_t(nx) * std::size_t(nz));
    std::vector<int> height(static_cast<std::size_t>(nx));
    std::vector<int> stack;
    stack.reserve(std::size_t(nx) + 1);
    for (int y0 = 0; y0 < ny; ++y0) {
        std::fill(columns.begin(), columns.end(), std::uint8_t(1));
        for (int y1 = y0; y1 < ny; ++y1) {
            bool any = false;
            for (int z = 0; z < nz; ++z)
                for (int x = 0; x < nx; ++x) {
                    std::uint8_t& col = columns[std::size_t(x) + std::size_t(nx) * std::size_t(z)];
                    col = std::uint8_t(col & mask[g.index(x, y1, z)]);
                    any = any || col;
                }
            if (!any) break;
            const std::size_t layers = std::size_t(y1 - y0 + 1);
            // Upper bound: even the whole layer cannot beat the best box.
            if (std::size_t(nx) * std::size_t(nz) * layers <= bestCells) continue;
            std::fill(height.begin(), height.end(), 0);
            for (int z = 0; z < nz; ++z) {
                for (int x = 0; x < nx; ++x) height[std::size_t(x)] = columns[std::size_t(x) + std::size_t(nx) * std::size_t(z)] ? height[std::size_t(x)] + 1 : 0;
                // Largest rectangle under the histogram of rows ending at z.
                stack.clear();
                for (int x = 0; x <= nx; ++x) {
                    const int h = x < nx ? height[std::size_t(x)] : 0;
                    while (!stack.empty() && height[std::size_t(stack.back())] >= h) {
                        const int top = stack.back();
                        stack.pop_back();
                        const int hTop = height[std::size_t(top)];
                        const int left = stack.empty() ? 0 : stack.back() + 1;
                        const std::size_t cells = std::size_t(hTop) * std::size_t(x - left) * layers;
                        if (hTop > 0 && cells > bestCells) {
                            bestCells = cells;
                            best.lo = {left, y0, z - hTop + 1};
                            best.hi = {x - 1, y1, z};
                        }
                    }
                    stack.push_back(x);
                }
            }
        }
    }
    return best;
}

// Whether every cell of the box is set in `mask` (false for boxes leaving the grid).
bool allSet(const Grid& g, const std::vector<std::uint8_t>& mask, const CellBox& b) {
    for (int a = 0; a < 3; ++a)
        if (b.lo[a] < 0 || b.hi[a] >= g.n[a]) return false;
    for (int z = b.lo.z; z <= b.hi.z; ++z)
        for (int y = b.lo.y; y <= b.hi.y; ++y)
            for (int x = b.lo.x; x <= b.hi.x; ++x)
                if (!mask[g.index(x, y, z)]) return false;
    return true;
}

// Grows a box one layer at a time in any direction whose new layer is all solid (covered or not):
// larger occluders hide more, overlap costs nothing.
CellBox grow(const Grid& g, const std::vector<std::uint8_t>& solid, CellBox box) {
    for (bool changed = true; changed;) {
        changed = false;
        for (int a = 0; a < 3; ++a)
            for (int side = 0; side < 2; ++side) {
                CellBox layer = box;
                if (side == 0) layer.lo[a] = layer.hi[a] = box.lo[a] - 1;
                else layer.lo[a] = layer.hi[a] = box.hi[a] + 1;
                if (!allSet(g, solid, layer)) continue;
                if (side == 0) box.lo[a] -= 1;
                else box.hi[a] += 1;
                changed = true;
            }
    }
    return box;
}

// The float box of a cell box moved in by the margin, rounded inwards so that it never grows.
AxisBox toAxisBox(const Grid& g, const CellBox& b, double margin) {
    AxisBox box;
    for (int a = 0; a < 3; ++a) {
        const double lo = g.plane(a, b.lo[a]) + margin * g.cell[a];
        const double hi = g.plane(a, b.hi[a] + 1) - margin * g.cell[a];
        float flo = float(lo), fhi = float(hi);
        if (double(flo) < lo) flo = std::nextafter(flo, std::numeric_limits<float>::infinity());
        if (double(fhi) > hi) fhi = std::nextafter(fhi, -std::numeric_limits<float>::infinity());
        box.min[a] = flo;
        box.max[a] = fhi;
    }
    return box;
}

}  // namespace

std::vector<AxisBox> fitOccluderBoxes(std::span<const MeshData* const> meshes, const OccluderFitOptions& options, OccluderFitStatistics* statistics) {
    checkOptions(options);
    const std::vector<Triangle> tris = gatherTriangles(meshes);
    OccluderFitStatistics stats;
    if (statistics) *statistics = stats;
    if (tris.empty()) return {};

    Grid g;
    g.lo = g.hi = tris[0].v[0];
    for (const Triangle& t : tris)
        for (const DVec3& v : t.v) {
            g.lo = glm::min(g.lo, v);
            g.hi = glm::max(g.hi, v);
        }
    const DVec3 extent = g.hi - g.lo;
    stats.boundsVolume = extent.x * extent.y * extent.z;
    const double longest = std::max({extent.x, extent.y, extent.z});
    // A flat or degenerate bounding box encloses no volume: nothing can be solid.
    if (!(longest > 0.0) || std::min({extent.x, extent.y, extent.z}) <= longest * 1e-6) {
        if (statistics) *statistics = stats;
        return {};
    }
    const double step = longest / options.resolution;
    for (int a = 0; a < 3; ++a) {
        g.n[a] = std::clamp(int(std::lround(extent[a] / step)), 1, options.resolution);
        g.cell[a] = extent[a] / g.n[a];
    }
    stats.cells = g.n;
    stats.cellSize = glm::vec3(g.cell);

    const SurfaceMarks marks = markSurface(g, tris);
    const std::vector<std::uint8_t>& surface = marks.cell;
    const std::vector<std::uint8_t> enclosed = enclosedCells(g, tris);
    const std::vector<std::uint8_t> solid = solidCells(g, marks, enclosed);
    const double cellVolume = g.cell.x * g.cell.y * g.cell.z;
    for (std::size_t i = 0; i < g.count(); ++i) {
        stats.surfaceCells += surface[i];
        stats.solidCells += solid[i];
    }
    stats.solidVolume = double(stats.solidCells) * cellVolume;

    std::vector<AxisBox> boxes;
    std::vector<std::uint8_t> uncovered = solid;
    std::size_t firstCells = 0;
    while (int(boxes.size()) < options.maxBoxes) {
        const CellBox seed = largestBox(g, uncovered);
        if (seed.cells() == 0) break;
        const CellBox box = boxes.empty() ? seed : grow(g, solid, seed);
        std::size_t gain = 0;
        for (int z = box.lo.z; z <= box.hi.z; ++z)
            for (int y = box.lo.y; y <= box.hi.y; ++y)
                for (int x = box.lo.x; x <= box.hi.x; ++x) gain += uncovered[g.index(x, y, z)];
        if (boxes.empty()) firstCells = gain;
        else if (double(gain) < options.minGain * double(firstCells)) break;
        for (int z = box.lo.z; z <= box.hi.z; ++z)
            for (int y = box.lo.y; y <= box.hi.y; ++y)
                for (int x = box.lo.x; x <= box.hi.x; ++x) uncovered[g.index(x, y, z)] = 0;
        const AxisBox fitted = toAxisBox(g, box, options.margin);
        if (fitted.empty()) break;
        boxes.push_back(fitted);
        stats.boxVolume += fitted.volume();
    }
    if (statistics) *statistics = stats;
    return boxes;
}

}  // namespace throng
