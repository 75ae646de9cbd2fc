#pragma once
// Where a draw item stands in the world: an affine transform kept as DRAW uploads it, its linear
// part (rotation and scale) in float and its translation in double. The translation keeps the
// precision of world positions 10^7 m from the origin; the linear part loses nothing DRAW would
// keep (it is rounded to float there anyway). 64 bytes where a double 4x4 matrix takes 128: a
// crowd writes one per drawn part every frame, and DRAW reads each once.

#include <cmath>

#include <glm/mat3x3.hpp>

#include "throng/scenegraph/Math.h"

namespace throng {

/// An affine placement: x -> linear * x + translation.
struct ItemTransform {
    Vec3 translation{0.0};      ///< where the item's origin is, in world space
    glm::mat3 linear{1.0f};     ///< rotation and scale (column-major), rounded to float

    ItemTransform() = default;
    /// The affine part of `m` (its last row is taken to be 0 0 0 1), the linear part rounded to float.
    explicit ItemTransform(const Mat4& m)
        : translation(m[3]), linear(glm::vec3(m[0]), glm::vec3(m[1]), glm::vec3(m[2])) {}

    /// As a double 4x4 matrix.
    Mat4 toMat4() const {
        Mat4 m{glm::dmat3(linear)};
        m[3] = Vec4(translation, 1.0);
        return m;
    }
    /// The item's point `p` (item frame) in world space.
    Vec3 transformPoint(const Vec3& p) const { return glm::dmat3(linear) * p + translation; }
    /// Equality of both parts.
    bool operator==(const ItemTransform&) const = default;
};

/// Whether every number of `t` is finite.
inline bool isFinite(const ItemTransform& t) {
    bool finite = std::isfinite(t.translation.x) && std::isfinite(t.translation.y) && std::isfinite(t.translation.z);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) finite = finite && std::isfinite(t.linear[c][r]);
    return finite;
}

}  // namespace throng
