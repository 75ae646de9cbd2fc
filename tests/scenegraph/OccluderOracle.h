#pragma once
// The independent check of fitted occluders: segments from eyes outside a model's bounding box to
// points on the boxes, each tested with an exact ray-triangle intersection (double precision, no
// tolerance) for a front face of the model (counter-clockwise seen from the eye, as the renderer
// draws it with back faces culled) crossed before the box point. Shared by the analytic and the
// asset tests.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "throng/scenegraph/AxisBox.h"
#include "throng/scenegraph/MeshData.h"

namespace throng::testkit {

/// One failing segment, for messages.
struct OracleMiss {
    glm::dvec3 eye, target;
    bool anyHit = false;  ///< whether the segment crossed a back face (but no front face) first
};

/// Result of probing boxes against a model.
struct OracleReport {
    int segments = 0;            ///< segments tested
    int misses = 0;              ///< segments reaching a box with no front face crossed before it
    int backFirst = 0;           ///< segments whose first crossing was a back face (still hidden later)
    std::vector<OracleMiss> examples;  ///< the first few misses
};

/// The model's triangles in double precision with their geometric (counter-clockwise) normals.
class TriangleSoup {
public:
    explicit TriangleSoup(std::span<const MeshData* const> meshes) {
        for (const MeshData* m : meshes)
            for (std::size_t i = 0; i + 2 < m->indices.size(); i += 3) {
                const glm::dvec3 a(m->positions[m->indices[i]]), b(m->positions[m->indices[i + 1]]), c(m->positions[m->indices[i + 2]]);
                a_.push_back(a);
                e1_.push_back(b - a);
                e2_.push_back(c - a);
                lo_ = count() == 1 ? glm::min(a, glm::min(b, c)) : glm::min(lo_, glm::min(a, glm::min(b, c)));
                hi_ = count() == 1 ? glm::max(a, glm::max(b, c)) : glm::max(hi_, glm::max(a, glm::max(b, c)));
            }
    }
    std::size_t count() const { return a_.size(); }
    const glm::dvec3& lo() const { return lo_; }
    const glm::dvec3& hi() const { return hi_; }

    /// Along the segment eye->target (parameter 0..1): whether a front face is crossed strictly
    /// before the target, and whether the very first crossing is a back face.
    void probe(const glm::dvec3& eye, const glm::dvec3& target, bool& frontBefore, bool& firstIsBack) const {
        const glm::dvec3 d = target - eye;
        double firstT = 2.0;
        bool firstFront = false;
        frontBefore = false;
        for (std::size_t i = 0; i < a_.size(); ++i) {
            // Moller-Trumbore without tolerance: a hit exactly on an edge counts, which is the
            // renderer's behaviour for a closed surface (one of the two triangles draws the pixel).
            const glm::dvec3 p = glm::cross(d, e2_[i]);
            const double det = glm::dot(e1_[i], p);
            if (det == 0.0) continue;
            const double inv = 1.0 / det;
            const glm::dvec3 s = eye - a_[i];
            const double u = glm::dot(s, p) * inv;
            if (u < 0.0 || u > 1.0) continue;
            const glm::dvec3 q = glm::cross(s, e1_[i]);
            const double v = glm::dot(d, q) * inv;
            if (v < 0.0 || u + v > 1.0) continue;
            const double t = glm::dot(e2_[i], q) * inv;
            if (!(t > 0.0 && t < 1.0)) continue;
            // det > 0 means the segment runs against the normal e1 x e2: the face is towards the eye.
            const bool front = det > 0.0;
            if (front) frontBefore = true;
            if (t < firstT) {
                firstT = t;
                firstFront = front;
            }
        }
        firstIsBack = firstT <= 1.0 && !firstFront;
    }

private:
    std::vector<glm::dvec3> a_, e1_, e2_;
    glm::dvec3 lo_{0.0}, hi_{0.0};
};

/// A random eye outside the box [lo, hi]: mostly anywhere around it, a quarter just outside a face
/// (1 mm to 2 % of the size away), some far out along a face's plane looking along the wall.
inline glm::dvec3 randomEyeOutside(std::mt19937_64& rng, const glm::dvec3& lo, const glm::dvec3& hi) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const glm::dvec3 size = hi - lo;
    const double longest = std::max({size.x, size.y, size.z});
    const double kind = unit(rng);
    if (kind < 0.6) {
        for (;;) {
            glm::dvec3 e;
            for (int a = 0; a < 3; ++a) e[a] = lo[a] - 1.5 * longest + unit(rng) * (size[a] + 3.0 * longest);
            bool inside = true;
            for (int a = 0; a < 3; ++a) inside = inside && e[a] >= lo[a] && e[a] <= hi[a];
            if (!inside) return e;
        }
    }
    const int axis = int(unit(rng) * 3.0) % 3;
    const bool up = unit(rng) < 0.5;
    const double away = longest * (0.0005 + 0.02 * unit(rng)) + 1e-3;
    glm::dvec3 e;
    for (int a = 0; a < 3; ++a) e[a] = lo[a] - 0.1 * size[a] + unit(rng) * 1.2 * size[a];
    e[axis] = up ? hi[axis] + away : lo[axis] - away;
    if (kind >= 0.85) {
        // Far out along the wall: grazing rays that skim the face on their way to the box.
        const int along = (axis + 1 + int(unit(rng) * 2.0) % 2) % 3;
        e[along] = unit(rng) < 0.5 ? lo[along] - longest * (0.2 + 2.0 * unit(rng)) : hi[along] + longest * (0.2 + 2.0 * unit(rng));
    }
    return e;
}

/// A random point on a face of `box` that faces `eye` (chosen by area), or false if none does.
inline bool randomPointFacing(std::mt19937_64& rng, const AxisBox& box, const glm::dvec3& eye, glm::dvec3& point) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const glm::dvec3 lo(box.min), hi(box.max), size = hi - lo;
    double area[6];
    double total = 0.0;
    for (int f = 0; f < 6; ++f) {
        const int a = f / 2;
        const bool up = f % 2 == 1;
        const bool facing = up ? eye[a] > hi[a] : eye[a] < lo[a];
        area[f] = facing ? size[(a + 1) % 3] * size[(a + 2) % 3] : 0.0;
        total += area[f];
    }
    if (!(total > 0.0)) return false;
    double pick = unit(rng) * total;
    int f = 0;
    while (f < 5 && (area[f] == 0.0 || pick > area[f])) {
        pick -= area[f];
        ++f;
    }
    const int a = f / 2;
    for (int k = 0; k < 3; ++k) point[k] = lo[k] + unit(rng) * size[k];
    point[a] = f % 2 == 1 ? hi[a] : lo[a];
    return true;
}

/// Probes `segments` random segments from eyes outside the soup's bounding box to the boxes.
inline OracleReport probeBoxes(const TriangleSoup& soup, std::span<const AxisBox> boxes, int segments, std::uint64_t seed) {
    OracleReport report;
    if (boxes.empty()) return report;
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<std::size_t> whichBox(0, boxes.size() - 1);
    while (report.segments < segments) {
        const glm::dvec3 eye = randomEyeOutside(rng, soup.lo(), soup.hi());
        glm::dvec3 target;
        if (!randomPointFacing(rng, boxes[whichBox(rng)], eye, target)) continue;
        ++report.segments;
        bool front = false, back = false;
        soup.probe(eye, target, front, back);
        report.backFirst += back;
        if (!front) {
            ++report.misses;
            if (report.examples.size() < 5) report.examples.push_back({eye, target, back});
        }
    }
    return report;
}

}  // namespace throng::testkit
