#pragma once
// A navigation mesh built with Recast from NavGeometry and queried with Detour: nearest points,
// deterministic random points, and the Detour objects DetourCrowd needs.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "throng/sim/NavGeometry.h"

class dtNavMesh;
class dtNavMeshQuery;

namespace throng::sim {

class CounterRng;

/// Recast build parameters (metres and degrees), the usual ones for people.
struct NavMeshSettings {
    float cellSize = 0.3f;            ///< voxel size across
    float cellHeight = 0.2f;          ///< voxel size up
    float agentHeight = 1.8f;         ///< clearance needed
    float agentRadius = 0.35f;        ///< kept away from walls
    float agentMaxClimb = 0.4f;       ///< steps climbed (kerbs)
    float agentMaxSlope = 45.0f;      ///< degrees
    float regionMinSize = 8.0f;       ///< cells (squared) below which regions are dropped
    float regionMergeSize = 20.0f;    ///< cells (squared) below which regions merge
    float edgeMaxLength = 12.0f;      ///< metres
    float edgeMaxError = 1.3f;        ///< cells
    float detailSampleDistance = 6.0f;///< cells
    float detailSampleMaxError = 1.0f;///< cells
    /// Side of a square Detour tile, metres; 0: the whole mesh is one tile (whose polygon mesh
    /// numbers vertices with 16 bits, which limits its size). Tiles are built in parallel.
    float tileSize = 0.0f;
};

/// A built navigation mesh.
class NavMesh {
public:
    /// Builds from `geometry`. Throws std::runtime_error naming the Recast or Detour step that
    /// failed (or std::invalid_argument if the geometry is empty or not finite).
    static std::shared_ptr<NavMesh> build(const NavGeometry& geometry, const NavMeshSettings& settings = {});
    /// The mesh as bytes (its settings, Detour's parameters, every tile's data and reference), for a
    /// process that did not build it: the ranks of a run receive rank 0's (fromBytes).
    std::vector<std::byte> toBytes() const;
    /// The mesh toBytes() wrote, with the same polygons under the same references, so that nearest
    /// and random points, paths and crowds on it are those of the original, bit for bit. Throws
    /// std::invalid_argument naming what is wrong: truncated, not such bytes, or a tile Detour refuses.
    /// Trusted input (the sender is a process of the same build): Detour reads tiles unchecked.
    static std::shared_ptr<NavMesh> fromBytes(std::span<const std::byte> bytes);
    ~NavMesh();
    NavMesh(const NavMesh&) = delete;
    NavMesh& operator=(const NavMesh&) = delete;

    /// The nearest point on the mesh within `halfExtents` of `p`, if any.
    std::optional<glm::vec3> nearestPoint(const glm::vec3& p, const glm::vec3& halfExtents = glm::vec3(2, 4, 2)) const;
    /// A random point on the mesh, area-weighted over all walkable polygons (a binary search of their
    /// running area, so its cost grows with the log of the mesh), a pure function of `rng` and `counter`.
    glm::vec3 randomPoint(const CounterRng& rng, std::uint64_t counter) const;
    /// The same point, found with the caller's own `query` (so that threads can draw in parallel).
    glm::vec3 randomPoint(const CounterRng& rng, std::uint64_t counter, dtNavMeshQuery& query) const;
    /// A new query object on this mesh for one thread's use (free it with dtFreeNavMeshQuery).
    dtNavMeshQuery* newQuery() const;
    /// Number of polygons.
    int polygonCount() const;
    /// The box holding every vertex of the mesh and of its detail surface (where agents stand):
    /// its lowest and highest corners.
    std::pair<glm::vec3, glm::vec3> bounds() const { return {lo_, hi_}; }
    /// The settings it was built with.
    const NavMeshSettings& settings() const { return settings_; }

    /// Detour's mesh (for DetourCrowd).
    dtNavMesh* detourMesh() const { return mesh_; }
    /// A query object for the calling thread's single use (not thread-safe).
    dtNavMeshQuery* query() const { return query_; }

private:
    NavMesh() = default;
    void indexPolygons();
    dtNavMesh* mesh_ = nullptr;
    std::vector<std::uint64_t> polyRefs_;  // walkable polygons, tile by tile
    std::vector<double> polyAreaSum_;      // running sum of their areas (for random points)
    dtNavMeshQuery* query_ = nullptr;
    NavMeshSettings settings_;
    glm::vec3 lo_{0.0f}, hi_{0.0f};        // bounds()
};

}  // namespace throng::sim
