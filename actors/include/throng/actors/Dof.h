#pragma once
// Degrees of freedom of a Skeleton node: rotations about an axis and translations along one, each
// with limits, or free orientation / position / scale (what glTF animations drive). A node's local
// matrix is T(rest + translations) * R(rest * orientation * axis rotations) * S(rest * scale).

#include <array>
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

namespace throng {

/// Kind of a degree of freedom, and so how many float values it takes.
enum class DofKind : std::uint8_t {
    RotateAxis,     ///< 1 value: angle in radians about `axis`, clamped to [min, max]
    TranslateAxis,  ///< 1 value: metres along `axis`, clamped to [min, max]
    Orientation,    ///< 4 values: unit quaternion (x, y, z, w)
    Position,       ///< 3 values: translation (x, y, z), metres
    Scale,          ///< 3 values: scale factors (x, y, z)
};

/// Number of float values a DOF of `kind` takes.
constexpr int dofValueCount(DofKind kind) {
    switch (kind) {
        case DofKind::RotateAxis:
        case DofKind::TranslateAxis: return 1;
        case DofKind::Orientation: return 4;
        case DofKind::Position:
        case DofKind::Scale: return 3;
    }
    return 0;
}

/// One degree of freedom of a Skeleton node.
struct Dof {
    DofKind kind = DofKind::RotateAxis;                     ///< what it moves
    glm::vec3 axis{0.0f, 0.0f, 1.0f};                       ///< unit axis (RotateAxis, TranslateAxis)
    float min = -std::numeric_limits<float>::infinity();   ///< lower limit (RotateAxis, TranslateAxis)
    float max = std::numeric_limits<float>::infinity();    ///< upper limit (RotateAxis, TranslateAxis)
    std::array<float, 4> rest{0.0f, 0.0f, 0.0f, 1.0f};      ///< value in the rest pose (first N used)

    /// A rotation about `axis` limited to [lo, hi] radians, resting at `at`.
    static Dof rotation(const glm::vec3& axis, float lo, float hi, float at = 0.0f) {
        return Dof{DofKind::RotateAxis, axis, lo, hi, {at, 0, 0, 0}};
    }
    /// A translation along `axis` limited to [lo, hi] metres, resting at `at`.
    static Dof translation(const glm::vec3& axis, float lo, float hi, float at = 0.0f) {
        return Dof{DofKind::TranslateAxis, axis, lo, hi, {at, 0, 0, 0}};
    }
};

}  // namespace throng
