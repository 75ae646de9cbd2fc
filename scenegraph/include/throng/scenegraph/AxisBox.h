#pragma once
// An axis-aligned box in some frame: the shape of occluders fitted inside static geometry, and of
// the shell around that geometry.

#include <glm/vec3.hpp>

namespace throng {

/// A box [min, max] along the axes of its frame.
struct AxisBox {
    glm::vec3 min{0.0f};  ///< smallest corner
    glm::vec3 max{0.0f};  ///< largest corner

    /// Whether it holds no volume (some max below or at its min).
    bool empty() const { return !(max.x > min.x && max.y > min.y && max.z > min.z); }
    /// Side lengths.
    glm::vec3 size() const { return max - min; }
    /// Volume (0 when empty).
    float volume() const { return empty() ? 0.0f : size().x * size().y * size().z; }
    /// Whether `p` lies inside or on it.
    bool contains(const glm::vec3& p) const {
        return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z && p.z <= max.z;
    }
    /// Corner `i` in 0..7: bit 0 picks max.x, bit 1 max.y, bit 2 max.z.
    glm::vec3 corner(int i) const {
        return glm::vec3((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
    }
};

}  // namespace throng
