#include "throng/scenegraph/MorphTarget.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "throng/scenegraph/MeshData.h"

namespace throng {

void applyMorphTargets(const MeshData& mesh, std::span<const float> weights, std::span<glm::vec3> positions,
                       std::span<glm::vec3> normals) {
    const auto fail = [&](const std::string& what) {
        throw std::invalid_argument("applyMorphTargets: mesh '" + mesh.name + "': " + what);
    };
    const std::size_t n = mesh.vertexCount();
    if (weights.size() != mesh.morphTargets.size())
        fail(std::to_string(weights.size()) + " weights for " + std::to_string(mesh.morphTargets.size()) + " morph targets");
    if (positions.size() != n) fail(std::to_string(positions.size()) + " output positions for " + std::to_string(n) + " vertices");
    const bool doNormals = !normals.empty() && !mesh.normals.empty();
    if (doNormals && normals.size() != n) fail(std::to_string(normals.size()) + " output normals for " + std::to_string(n) + " vertices");
    for (float w : weights)
        if (!std::isfinite(w)) fail("a weight is not finite");
    std::copy(mesh.positions.begin(), mesh.positions.end(), positions.begin());
    if (doNormals) std::copy(mesh.normals.begin(), mesh.normals.end(), normals.begin());
    // Target by target, as the vertex shader adds them (the same order of float additions).
    for (std::size_t t = 0; t < weights.size(); ++t) {
        const float w = std::clamp(weights[t], -kMaxMorphWeight, kMaxMorphWeight);
        if (w == 0.0f) continue;
        const MorphTarget& m = mesh.morphTargets[t];
        for (std::size_t v = 0; v < n; ++v) positions[v] += w * m.positions[v];
        if (doNormals && !m.normals.empty())
            for (std::size_t v = 0; v < n; ++v) normals[v] += w * m.normals[v];
    }
}

}  // namespace throng
