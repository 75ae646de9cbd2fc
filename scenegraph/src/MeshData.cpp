#include "throng/scenegraph/MeshData.h"
#include "throng/scenegraph/BodyLook.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace throng {
namespace {

[[noreturn]] void fail(const MeshData& m, const std::string& what) {
    throw std::invalid_argument("mesh '" + m.name + "': " + what);
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void MeshData::validate() const {
    const std::size_t n = positions.size();
    if (n == 0) fail(*this, "has no vertices");
    if (!normals.empty() && normals.size() != n) fail(*this, "has " + std::to_string(normals.size()) + " normals for " + std::to_string(n) + " vertices");
    if (!texcoords.empty() && texcoords.size() != n) fail(*this, "has " + std::to_string(texcoords.size()) + " texture coordinates for " + std::to_string(n) + " vertices");
    if (joints0.size() != weights0.size() || (!joints0.empty() && joints0.size() != n))
        fail(*this, "has skin influence arrays (joints0/weights0) whose sizes do not match the vertex count");
    if (joints1.size() != weights1.size() || (!joints1.empty() && joints1.size() != n) || (!joints1.empty() && joints0.empty()))
        fail(*this, "has skin influence arrays (joints1/weights1) whose sizes do not match the vertex count");
    if (!regions.empty() && regions.size() != n) fail(*this, "has " + std::to_string(regions.size()) + " body regions for " + std::to_string(n) + " vertices");
    for (std::size_t i = 0; i < regions.size(); ++i)
        if (regions[i] > kBodyRegionCount) fail(*this, "vertex " + std::to_string(i) + " has body region " + std::to_string(regions[i]) + ", not 0-4");
    if (indices.size() % 3 != 0) fail(*this, "has " + std::to_string(indices.size()) + " indices, not a multiple of 3");
    for (std::size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= n) fail(*this, "index " + std::to_string(i) + " refers to vertex " + std::to_string(indices[i]) + " of " + std::to_string(n));
    for (std::size_t i = 0; i < n; ++i)
        if (!finite(positions[i])) fail(*this, "position " + std::to_string(i) + " is not finite");
    if (baseColorTexture && !baseColorTexture->valid()) fail(*this, "has an invalid base colour texture");
    for (std::size_t t = 0; t < morphTargets.size(); ++t) {
        const MorphTarget& m = morphTargets[t];
        const std::string which = "morph target " + std::to_string(t) + (m.name.empty() ? std::string() : " '" + m.name + "'");
        if (m.name.empty()) fail(*this, which + " has no name");
        for (std::size_t u = 0; u < t; ++u)
            if (morphTargets[u].name == m.name) fail(*this, which + " has the name of morph target " + std::to_string(u));
        if (m.positions.size() != n) fail(*this, which + " has " + std::to_string(m.positions.size()) + " position offsets for " + std::to_string(n) + " vertices");
        if (!m.normals.empty() && (normals.empty() || m.normals.size() != n))
            fail(*this, which + " has " + std::to_string(m.normals.size()) + " normal offsets for " + std::to_string(normals.size()) + " normals");
        for (std::size_t i = 0; i < n; ++i)
            if (!finite(m.positions[i]) || (!m.normals.empty() && !finite(m.normals[i])))
                fail(*this, which + ": the offset of vertex " + std::to_string(i) + " is not finite");
        if (!std::isfinite(m.defaultWeight)) fail(*this, which + " has a non-finite default weight");
    }
}

int MeshData::findMorphTarget(const std::string& targetName) const {
    for (std::size_t t = 0; t < morphTargets.size(); ++t)
        if (morphTargets[t].name == targetName) return static_cast<int>(t);
    return -1;
}

std::uint32_t MeshData::strongestJoint(std::size_t v) const {
    std::uint32_t best = joints0[v][0];
    float bestWeight = weights0[v][0];
    for (int c = 1; c < influenceCount(); ++c) {
        const float w = c < 4 ? weights0[v][c] : weights1[v][c - 4];
        if (w > bestWeight) bestWeight = w, best = c < 4 ? joints0[v][c] : joints1[v][c - 4];
    }
    return best;
}

BoundingSphere MeshData::computeBound() const {
    if (positions.empty()) fail(*this, "has no vertices to bound");
    // Centre of the axis-aligned box, then the farthest vertex: never too small, close to minimal.
    glm::dvec3 lo(positions[0]), hi(positions[0]);
    for (const glm::vec3& p : positions) {
        lo = glm::min(lo, glm::dvec3(p));
        hi = glm::max(hi, glm::dvec3(p));
    }
    const glm::dvec3 c = 0.5 * (lo + hi);
    double r2 = 0.0;
    for (const glm::vec3& p : positions) {
        const glm::dvec3 d = glm::dvec3(p) - c;
        r2 = std::max(r2, glm::dot(d, d));
    }
    // Any mix of targets moves a vertex by at most the sum of their largest offsets.
    double reach = 0.0;
    for (const MorphTarget& m : morphTargets) {
        double largest = 0.0;
        for (const glm::vec3& d : m.positions) largest = std::max(largest, glm::length(glm::dvec3(d)));
        reach += kMaxMorphWeight * largest;
    }
    return BoundingSphere(c, (std::sqrt(r2) + reach) * (1.0 + 1e-7));
}

}  // namespace throng
