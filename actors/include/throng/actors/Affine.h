#pragma once
// A rigid-or-scaled affine transform in float (3x3 linear part + translation): the matrices of
// Skeleton nodes relative to their actor's Skeleton Root. Actors are small, so float keeps them
// exact to micrometres; world placement is done once per actor in double. The type is a template
// over its scalar only so that tests can run the same pose code on an operation-counting type.

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpTally.h"
#include "throng/scenegraph/detail/ScalarMath.h"

namespace throng {

/// y = linear * x + translation, over scalar `S` (Affine: float).
template <class S>
struct BasicAffine {
    glm::mat<3, 3, S, glm::defaultp> linear{S(1)};      ///< rotation and scale (column-major)
    glm::vec<3, S, glm::defaultp> translation{S(0)};    ///< offset

    /// this * other (36 mults, 27 adds).
    BasicAffine operator*(const BasicAffine& other) const {
        return BasicAffine{linear * other.linear, linear * other.translation + translation};
    }
    /// Applies the transform to a point.
    glm::vec<3, S, glm::defaultp> transformPoint(const glm::vec<3, S, glm::defaultp>& p) const {
        return linear * p + translation;
    }
    /// As a 4x4 matrix of the same scalar.
    glm::mat<4, 4, S, glm::defaultp> toMat4() const {
        glm::mat<4, 4, S, glm::defaultp> m{linear};
        m[3] = glm::vec<4, S, glm::defaultp>(translation, S(1));
        return m;
    }
    /// As a world-precision (double) 4x4 matrix.
    glm::mat<4, 4, detail::Wide<S>, glm::defaultp> toDMat4() const {
        using W = detail::Wide<S>;
        glm::mat<4, 4, W, glm::defaultp> m{glm::mat<3, 3, W, glm::defaultp>(linear)};
        m[3] = glm::vec<4, W, glm::defaultp>(glm::vec<3, W, glm::defaultp>(translation), W(1));
        return m;
    }
};

/// The transform of a Skeleton node relative to its Skeleton Root.
using Affine = BasicAffine<float>;

/// a * b with its cost accounted (36 mults, 27 adds) when `ops` is non-null.
template <class S>
inline BasicAffine<S> compose(const BasicAffine<S>& a, const BasicAffine<S>& b, OpTally* ops) {
    THRONG_TALLY(ops, 36, 27, 0, 0);
    return a * b;
}

}  // namespace throng
