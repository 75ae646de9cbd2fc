#pragma once
// Triangles a navigation mesh is built from: surfaces actors may walk on (roads, pavement) and
// obstacles (buildings, trees) that block them, in metres with Y up.

#include <cstdint>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace throng {
struct MeshData;
}

namespace throng::sim {

/// A triangle soup with one flag per triangle.
struct NavGeometry {
    std::vector<glm::vec3> vertices;     ///< positions
    std::vector<std::uint32_t> indices;  ///< three per triangle
    std::vector<std::uint8_t> walkable;  ///< per triangle: 1 walkable surface, 0 obstacle
    /// Volumes nobody may stand in (building footprints): Recast voxelises surfaces, so without
    /// them the ground inside a closed building would be walkable.
    std::vector<std::pair<glm::vec3, glm::vec3>> blocked;

    /// Appends `mesh` placed by `transform`, every triangle walkable or an obstacle.
    void add(const MeshData& mesh, const glm::mat4& transform, bool isWalkable);
    /// Appends an axis-aligned box from `lo` to `hi`: a walkable slab, or an obstacle whose volume
    /// is also blocked.
    void addBox(const glm::vec3& lo, const glm::vec3& hi, bool isWalkable);
    /// Blocks the volume from `lo` to `hi` (extending it down to reach the ground below).
    void addBlocked(const glm::vec3& lo, const glm::vec3& hi) { blocked.emplace_back(lo, hi); }
    /// Number of triangles.
    std::size_t triangleCount() const { return indices.size() / 3; }
};

}  // namespace throng::sim
