#pragma once
// A rigid-or-scaled affine transform in float (3x3 linear part + translation): the matrices of
// Skeleton nodes relative to their actor's Skeleton Root. Actors are small, so float keeps them
// exact to micrometres; world placement is done once per actor in double.

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

/// y = linear * x + translation.
struct Affine {
    glm::mat3 linear{1.0f};        ///< rotation and scale (column-major)
    glm::vec3 translation{0.0f};   ///< offset

    /// this * other (36 mults, 27 adds).
    Affine operator*(const Affine& other) const {
        return Affine{linear * other.linear, linear * other.translation + translation};
    }
    /// Applies the transform to a point.
    glm::vec3 transformPoint(const glm::vec3& p) const { return linear * p + translation; }
    /// As a float 4x4 matrix.
    glm::mat4 toMat4() const {
        glm::mat4 m{linear};
        m[3] = glm::vec4(translation, 1.0f);
        return m;
    }
    /// As a double 4x4 matrix.
    Mat4 toDMat4() const {
        Mat4 m{glm::dmat3(linear)};
        m[3] = Vec4(Vec3(translation), 1.0);
        return m;
    }
};

/// a * b with its cost accounted (36 mults, 27 adds) when `ops` is non-null.
inline Affine compose(const Affine& a, const Affine& b, OpTally* ops) {
    THRONG_TALLY(ops, 36, 27, 0, 0);
    return a * b;
}

}  // namespace throng
