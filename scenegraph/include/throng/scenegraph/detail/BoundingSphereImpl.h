#pragma once
// The operations of BasicBoundingSphere, written once over the scalar type: BoundingSphere.cpp
// compiles them for double (the library's BoundingSphere), the FMULT tests for a counting type.
// Every THRONG_TALLY states the operations of the code just above or below it, comparisons
// (the emptiness test radius >= 0 included) counted as additions.

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/Validation.h"
#include "throng/scenegraph/detail/ScalarMath.h"

namespace throng::detail {

/// `radius` padded so that the sphere stays conservative after rounding: a computed centre is off
/// by at most a few ulps of its coordinates and of the radius (~5e-8 m at 10^7 m from the origin).
template <class S>
S paddedRadius(const glm::vec<3, S, glm::defaultp>& center, S radius, OpTally* ops) {
    constexpr double kPadUlps = 8.0 * std::numeric_limits<double>::epsilon();
    THRONG_TALLY(ops, 1, 4, 0, 0);
    return radius + S(kPadUlps) * (absOf(center.x) + absOf(center.y) + absOf(center.z) + radius);
}

/// Upper bound of the spectral norm of the linear part of `m` (see throng::maxScaleFactor).
template <class S>
S maxScaleFactor(const glm::mat<4, 4, S, glm::defaultp>& m, OpTally* ops) {
    using V = glm::vec<3, S, glm::defaultp>;
    // Gram matrix G = L^T L of the linear part L; its largest eigenvalue is the squared spectral
    // norm, bounded above by the largest absolute row sum (Gershgorin), exactly when G is diagonal.
    const V c0(m[0]), c1(m[1]), c2(m[2]);
    const S g00 = glm::dot(c0, c0), g11 = glm::dot(c1, c1), g22 = glm::dot(c2, c2);
    const S g01 = absOf(glm::dot(c0, c1)), g02 = absOf(glm::dot(c0, c2)), g12 = absOf(glm::dot(c1, c2));
    const S bound = std::max({g00 + g01 + g02, g11 + g01 + g12, g22 + g02 + g12});
    THRONG_TALLY(ops, 18, 20, 0, 1);  // six dot products, six sums, two comparisons, the root
    return sqrtOf(bound);
}

}  // namespace throng::detail

namespace throng {

template <class S>
BasicBoundingSphere<S>::BasicBoundingSphere(const Vec& center, S radius) : center_(center), radius_(radius) {
    if constexpr (std::is_same_v<S, double>) {
        requireFinite(center, "BoundingSphere", "center");
        requireFinite(radius, "BoundingSphere", "radius");
        if (radius < 0.0)
            throw std::invalid_argument("BoundingSphere: argument 'radius' is negative (" + std::to_string(radius) + ")");
    }
}

template <class S>
void BasicBoundingSphere<S>::expandBy(const Vec& point, OpTally* ops) {
    if constexpr (std::is_same_v<S, double>) requireFinite(point, "BoundingSphere::expandBy", "point");
    if (!valid()) {
        THRONG_TALLY(ops, 0, 1, 0, 0);  // the emptiness test
        center_ = point;
        radius_ = S(0);
        return;
    }
    const Vec d = point - center_;
    const S d2 = glm::dot(d, d);
    THRONG_TALLY(ops, 4, 7, 0, 0);  // emptiness test, difference, squared length, compare against r^2
    if (d2 <= radius_ * radius_) return;
    const S dist = detail::sqrtOf(d2);
    const S newRadius = S(0.5) * (radius_ + dist);
    center_ += d * ((newRadius - radius_) / dist);
    THRONG_TALLY(ops, 4, 5, 1, 1);
    radius_ = detail::paddedRadius(center_, newRadius, ops);
}

template <class S>
void BasicBoundingSphere<S>::expandBy(const BasicBoundingSphere& sphere, OpTally* ops) {
    if (!sphere.valid()) {
        THRONG_TALLY(ops, 0, 1, 0, 0);
        return;
    }
    if (!valid()) {
        THRONG_TALLY(ops, 0, 2, 0, 0);
        *this = sphere;
        return;
    }
    const Vec d = sphere.center_ - center_;
    const S dist = detail::sqrtOf(glm::dot(d, d));
    THRONG_TALLY(ops, 3, 9, 0, 1);  // two emptiness tests, difference, length, first containment test
    if (dist + sphere.radius_ <= radius_) return;  // the other sphere is inside this one
    THRONG_TALLY(ops, 0, 2, 0, 0);
    if (dist + radius_ <= sphere.radius_) {  // this sphere is inside the other (coincident centres too)
        *this = sphere;
        return;
    }
    // Neither contains the other, so dist > |r1 - r2| >= 0 and the division is safe.
    const S newRadius = S(0.5) * (dist + radius_ + sphere.radius_);
    center_ += d * ((newRadius - radius_) / dist);
    THRONG_TALLY(ops, 4, 6, 1, 0);
    radius_ = detail::paddedRadius(center_, newRadius, ops);
}

template <class S>
void BasicBoundingSphere<S>::inflate(S margin) {
    if constexpr (std::is_same_v<S, double>) {
        requireFinite(margin, "BoundingSphere::inflate", "margin");
        if (margin < 0.0)
            throw std::invalid_argument("BoundingSphere::inflate: argument 'margin' is negative (" +
                                        std::to_string(margin) + ")");
    }
    if (valid()) radius_ += margin;
}

template <class S>
BasicBoundingSphere<S> BasicBoundingSphere<S>::transformed(const Mat& m, OpTally* ops) const {
    if (!valid()) {
        THRONG_TALLY(ops, 0, 1, 0, 0);
        return {};
    }
    BasicBoundingSphere out;
    out.center_ = Vec(m[0]) * center_.x + Vec(m[1]) * center_.y + Vec(m[2]) * center_.z + Vec(m[3]);
    THRONG_TALLY(ops, 9, 10, 0, 0);  // emptiness test, centre
    const S r = radius_ * detail::maxScaleFactor(m, ops);
    THRONG_TALLY(ops, 1, 0, 0, 0);
    out.radius_ = detail::paddedRadius(out.center_, r, ops);
    if (!detail::isFiniteOf(out.radius_) || !detail::isFiniteOf(out.center_.x) || !detail::isFiniteOf(out.center_.y) ||
        !detail::isFiniteOf(out.center_.z))
        throw std::invalid_argument("BoundingSphere::transformed: argument 'm' is not finite or overflows");
    return out;
}

template <class S>
bool BasicBoundingSphere<S>::contains(const Vec& point) const {
    if (!valid()) return false;
    const Vec d = point - center_;
    return glm::dot(d, d) <= radius_ * radius_;
}

template <class S>
bool BasicBoundingSphere<S>::contains(const BasicBoundingSphere& sphere) const {
    if (!sphere.valid()) return true;
    if (!valid()) return false;
    return glm::length(sphere.center_ - center_) + sphere.radius_ <= radius_;
}

}  // namespace throng
