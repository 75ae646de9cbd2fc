#pragma once
// The figure's own surface as a warping proxy for impostor cells: the skinned mesh (optionally
// decimated by clustering vertices of the same joint) at every key-frame of an impostor, in the
// actor frame. Its projected vertices are dense automatic point features whose triangles are seed
// 003's image patches: each triangle carries its depth, so where limbs overlap the nearer surface
// wins, and a cell can be warped from any stored cell (another key-frame, another view) to any
// key-frame and eye direction.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace throng {

/// A triangle mesh with one vertex position set per key-frame, and the projection of impostor cells.
class ProxyMesh {
public:
    /// A proxy of `vertices` vertices and `keyframes` (>= 1) key-frames for cells of `cellSize`
    /// (>= 1) pixels covering the square of half-size `radius` (> 0 metres) around `centre`, as the
    /// baker's views do. Positions start at the centre. Throws std::invalid_argument for values out
    /// of range.
    ProxyMesh(std::size_t vertices, int keyframes, const glm::vec3& centre, float radius, int cellSize);

    /// Number of vertices.
    std::size_t vertexCount() const { return vertices_; }
    /// Number of key-frames.
    int keyframeCount() const { return keyframes_; }
    /// Cell side in pixels.
    int cellSize() const { return cellSize_; }
    /// Triangles (vertex indices).
    const std::vector<std::array<std::uint32_t, 3>>& triangles() const { return triangles_; }
    /// Sets the triangles. Throws std::invalid_argument if an index is out of range.
    void setTriangles(std::vector<std::array<std::uint32_t, 3>> triangles);
    /// Positions (actor frame, metres) of key-frame `k`.
    std::span<const glm::vec3> positions(int keyframe) const;
    /// Sets the positions of key-frame `k` (vertexCount() finite points). Throws
    /// std::invalid_argument for a bad key-frame, size or value.
    void setPositions(int keyframe, std::span<const glm::vec3> positions);

    /// Positions at fractional key-frame `keyframe` (the clip loops: wrapped into [0, count)),
    /// linearly between the two key-frames around it; exactly positions(k) at a whole k. Throws
    /// std::invalid_argument if it is not finite.
    std::vector<glm::vec3> positionsAt(double keyframe) const;
    /// The vertices at (fractional) key-frame `keyframe` seen from `toEye` (needs a horizontal
    /// component): x, y in cell pixels (rows down, as FeatureTrack::lines), z the depth toward the
    /// eye in pixels.
    std::vector<glm::vec3> project(double keyframe, const glm::vec3& toEye) const;

    /// Unit vertex normals (actor frame) at (fractional) key-frame `keyframe`: area-weighted sums
    /// of the normals of the triangles around each vertex (counter-clockwise front faces); zero for
    /// a vertex of no triangle.
    std::vector<glm::vec3> normals(double keyframe) const;

    /// Bytes of this proxy (what storing it beside an atlas costs).
    std::size_t bytes() const;

private:
    std::size_t vertices_;
    int keyframes_;
    glm::vec3 centre_;
    float radius_;
    int cellSize_;
    std::vector<glm::vec3> positions_;  // [keyframe][vertex]
    std::vector<std::array<std::uint32_t, 3>> triangles_;
};

}  // namespace throng
