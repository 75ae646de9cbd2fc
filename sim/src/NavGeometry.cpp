#include "throng/sim/NavGeometry.h"

#include "throng/scenegraph/MeshData.h"

namespace throng::sim {

void NavGeometry::add(const MeshData& mesh, const glm::mat4& transform, bool isWalkable) {
    const auto base = static_cast<std::uint32_t>(vertices.size());
    for (const glm::vec3& p : mesh.positions) vertices.push_back(glm::vec3(transform * glm::vec4(p, 1.0f)));
    for (std::uint32_t i : mesh.indices) indices.push_back(base + i);
    walkable.insert(walkable.end(), mesh.indices.size() / 3, isWalkable ? 1 : 0);
}

void NavGeometry::addBox(const glm::vec3& lo, const glm::vec3& hi, bool isWalkable) {
    const auto base = static_cast<std::uint32_t>(vertices.size());
    for (int k = 0; k < 8; ++k) vertices.emplace_back(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
    // Six faces, wound counter-clockwise seen from outside (Recast reads the top faces' slope).
    const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        indices.insert(indices.end(), {base + f[0], base + f[1], base + f[2], base + f[0], base + f[2], base + f[3]});
        walkable.insert(walkable.end(), 2, isWalkable ? 1 : 0);
    }
    if (!isWalkable) addBlocked(lo, hi);
}

}  // namespace throng::sim
