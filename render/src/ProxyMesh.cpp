#include "throng/render/ProxyMesh.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "throng/render/FeatureTrack.h"

namespace throng {

ProxyMesh::ProxyMesh(std::size_t vertices, int keyframes, const glm::vec3& centre, float radius, int cellSize)
    : vertices_(vertices), keyframes_(keyframes), centre_(centre), radius_(radius), cellSize_(cellSize) {
    if (keyframes < 1) throw std::invalid_argument("ProxyMesh: at least one key-frame, got " + std::to_string(keyframes));
    if (!(radius > 0.0f) || !std::isfinite(radius)) throw std::invalid_argument("ProxyMesh: the radius must be positive and finite");
    if (cellSize < 1) throw std::invalid_argument("ProxyMesh: the cell size must be positive");
    if (!std::isfinite(centre.x) || !std::isfinite(centre.y) || !std::isfinite(centre.z))
        throw std::invalid_argument("ProxyMesh: the centre is not finite");
    positions_.assign(vertices * static_cast<std::size_t>(keyframes), centre);
}

void ProxyMesh::setTriangles(std::vector<std::array<std::uint32_t, 3>> triangles) {
    for (std::size_t i = 0; i < triangles.size(); ++i)
        for (std::uint32_t v : triangles[i])
            if (v >= vertices_)
                throw std::invalid_argument("ProxyMesh::setTriangles: triangle " + std::to_string(i) + " has vertex " + std::to_string(v) +
                                            " of " + std::to_string(vertices_));
    triangles_ = std::move(triangles);
}

std::span<const glm::vec3> ProxyMesh::positions(int keyframe) const {
    if (keyframe < 0 || keyframe >= keyframes_) throw std::invalid_argument("ProxyMesh: key-frame " + std::to_string(keyframe) + " out of range");
    return {positions_.data() + static_cast<std::size_t>(keyframe) * vertices_, vertices_};
}

void ProxyMesh::setPositions(int keyframe, std::span<const glm::vec3> positions) {
    if (keyframe < 0 || keyframe >= keyframes_)
        throw std::invalid_argument("ProxyMesh::setPositions: key-frame " + std::to_string(keyframe) + " out of range");
    if (positions.size() != vertices_)
        throw std::invalid_argument("ProxyMesh::setPositions: " + std::to_string(positions.size()) + " positions for " +
                                    std::to_string(vertices_) + " vertices");
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const glm::vec3& p = positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw std::invalid_argument("ProxyMesh::setPositions: vertex " + std::to_string(i) + " is not finite");
        positions_[static_cast<std::size_t>(keyframe) * vertices_ + i] = p;
    }
}

std::vector<glm::vec3> ProxyMesh::positionsAt(double keyframe) const {
    if (!std::isfinite(keyframe)) throw std::invalid_argument("ProxyMesh: the key-frame is not finite");
    const double count = static_cast<double>(keyframes_);
    double k = std::fmod(keyframe, count);
    if (k < 0.0) k += count;
    const int k0 = std::min(static_cast<int>(k), keyframes_ - 1);
    const int k1 = (k0 + 1) % keyframes_;
    const auto f = static_cast<float>(k - k0);
    const std::span<const glm::vec3> a = positions(k0);
    if (f == 0.0f) return {a.begin(), a.end()};
    const std::span<const glm::vec3> b = positions(k1);
    std::vector<glm::vec3> out(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) out[i] = a[i] + (b[i] - a[i]) * f;
    return out;
}

std::vector<glm::vec3> ProxyMesh::project(double keyframe, const glm::vec3& toEye) const {
    const ViewBasis b = viewBasis(toEye);
    const std::vector<glm::vec3> p = positionsAt(keyframe);
    const float s = static_cast<float>(cellSize_), ppm = s / (2.0f * radius_);
    std::vector<glm::vec3> out(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::vec3 r = p[i] - centre_;
        out[i] = {(glm::dot(b.right, r) / radius_ * 0.5f + 0.5f) * s, (0.5f - 0.5f * glm::dot(b.up, r) / radius_) * s,
                  glm::dot(b.toEye, r) * ppm};
    }
    return out;
}

std::vector<glm::vec3> ProxyMesh::normals(double keyframe) const {
    const std::vector<glm::vec3> p = positionsAt(keyframe);
    std::vector<glm::vec3> n(p.size(), glm::vec3(0.0f));
    for (const auto& t : triangles_) {
        const glm::vec3 face = glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);  // length: twice the area
        for (std::uint32_t v : t) n[v] += face;
    }
    for (glm::vec3& v : n) {
        const float len = glm::length(v);
        v = len > 0.0f ? v / len : glm::vec3(0.0f);
    }
    return n;
}

std::size_t ProxyMesh::bytes() const { return positions_.size() * sizeof(glm::vec3) + triangles_.size() * sizeof(triangles_[0]); }

}  // namespace throng
