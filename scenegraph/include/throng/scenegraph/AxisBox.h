#pragma once
// An axis-aligned box in float, in the frame of the geometry it belongs to (mesh frame). Occluder
// shapes are kept as these: eight corners are all a depth rasteriser needs, and float matches the
// meshes they are fitted inside.

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace throng {

/// A closed axis-aligned box [min, max]. A box whose max is below its min on some axis is empty;
/// the default box is the single point at the origin (not empty, volume 0).
struct AxisBox {
    glm::vec3 min{0.0f};  ///< smallest corner
    glm::vec3 max{0.0f};  ///< largest corner

    /// Whether the box holds no point (max < min on some axis).
    bool empty() const { return max.x < min.x || max.y < min.y || max.z < min.z; }
    /// Edge lengths (zero for an empty box).
    glm::vec3 size() const { return glm::max(max - min, glm::vec3(0.0f)); }
    /// The centre (meaningless for an empty box).
    glm::vec3 center() const { return 0.5f * (min + max); }
    /// Volume (zero for an empty box), computed in double so that large thin boxes keep precision.
    double volume() const {
        const glm::vec3 s = size();
        return double(s.x) * double(s.y) * double(s.z);
    }
    /// Whether `p` lies inside or on the box.
    bool contains(const glm::vec3& p) const {
        return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z && p.z <= max.z;
    }
    /// Whether `b` lies entirely inside or on this box (an empty box is inside anything).
    bool contains(const AxisBox& b) const { return b.empty() || (contains(b.min) && contains(b.max)); }
    /// Corner `i` in 0..7: bit 0 picks max.x, bit 1 max.y, bit 2 max.z (clear bits pick min).
    glm::vec3 corner(int i) const {
        return {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
    }
    /// The box moved in by `d` on every side (out when negative); may become empty.
    AxisBox shrunk(float d) const { return {min + glm::vec3(d), max - glm::vec3(d)}; }
    /// Exact equality, for tests.
    bool operator==(const AxisBox&) const = default;
};

}  // namespace throng
