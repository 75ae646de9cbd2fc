#include "throng/scenegraph/BoundingSphere.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "throng/scenegraph/Validation.h"

namespace throng {
namespace {

// Rounding in a computed centre is at most a few ulps of its coordinates and of the radius; padding
// the radius by this much keeps every result conservative, even 10^7 m from the origin (~5e-8 m).
constexpr double kPadUlps = 8.0 * std::numeric_limits<double>::epsilon();

double padded(const Vec3& center, double radius, OpTally* ops) {
    THRONG_TALLY(ops, 1, 4, 0, 0);
    return radius + kPadUlps * (std::abs(center.x) + std::abs(center.y) + std::abs(center.z) + radius);
}

}  // namespace

BoundingSphere::BoundingSphere(const Vec3& center, double radius) : center_(center), radius_(radius) {
    requireFinite(center, "BoundingSphere", "center");
    requireFinite(radius, "BoundingSphere", "radius");
    if (radius < 0.0)
        throw std::invalid_argument("BoundingSphere: argument 'radius' is negative (" +
                                    std::to_string(radius) + ")");
}

void BoundingSphere::expandBy(const Vec3& point, OpTally* ops) {
    requireFinite(point, "BoundingSphere::expandBy", "point");
    if (!valid()) {
        center_ = point;
        radius_ = 0.0;
        return;
    }
    const Vec3 d = point - center_;
    const double d2 = glm::dot(d, d);
    THRONG_TALLY(ops, 4, 6, 0, 0);  // difference, squared length, compare against r^2
    if (d2 <= radius_ * radius_) return;
    const double dist = std::sqrt(d2);
    const double newRadius = 0.5 * (radius_ + dist);
    center_ += d * ((newRadius - radius_) / dist);
    THRONG_TALLY(ops, 4, 5, 1, 1);
    radius_ = padded(center_, newRadius, ops);
}

void BoundingSphere::expandBy(const BoundingSphere& sphere, OpTally* ops) {
    if (!sphere.valid()) return;
    if (!valid()) {
        *this = sphere;
        return;
    }
    const Vec3 d = sphere.center_ - center_;
    const double dist = std::sqrt(glm::dot(d, d));
    THRONG_TALLY(ops, 3, 7, 0, 1);  // difference, length, first containment test
    if (dist + sphere.radius_ <= radius_) return;  // the other sphere is inside this one
    THRONG_TALLY(ops, 0, 2, 0, 0);
    if (dist + radius_ <= sphere.radius_) {  // this sphere is inside the other (coincident centres too)
        *this = sphere;
        return;
    }
    // Neither contains the other, so dist > |r1 - r2| >= 0 and the division is safe.
    const double newRadius = 0.5 * (dist + radius_ + sphere.radius_);
    center_ += d * ((newRadius - radius_) / dist);
    THRONG_TALLY(ops, 4, 6, 1, 0);
    radius_ = padded(center_, newRadius, ops);
}

void BoundingSphere::inflate(double margin) {
    requireFinite(margin, "BoundingSphere::inflate", "margin");
    if (margin < 0.0)
        throw std::invalid_argument("BoundingSphere::inflate: argument 'margin' is negative (" +
                                    std::to_string(margin) + ")");
    if (valid()) radius_ += margin;
}

double maxScaleFactor(const Mat4& m, OpTally* ops) {
    // Gram matrix G = L^T L of the linear part L; its largest eigenvalue is the squared spectral
    // norm, bounded above by the largest absolute row sum (Gershgorin), exactly when G is diagonal.
    const Vec3 c0(m[0]), c1(m[1]), c2(m[2]);
    const double g00 = glm::dot(c0, c0), g11 = glm::dot(c1, c1), g22 = glm::dot(c2, c2);
    const double g01 = std::abs(glm::dot(c0, c1)), g02 = std::abs(glm::dot(c0, c2)),
                 g12 = std::abs(glm::dot(c1, c2));
    const double bound = std::max({g00 + g01 + g02, g11 + g01 + g12, g22 + g02 + g12});
    THRONG_TALLY(ops, 18, 20, 0, 1);
    return std::sqrt(bound);
}

BoundingSphere BoundingSphere::transformed(const Mat4& m, OpTally* ops) const {
    if (!valid()) return {};
    BoundingSphere out;
    out.center_ = Vec3(m[0]) * center_.x + Vec3(m[1]) * center_.y + Vec3(m[2]) * center_.z + Vec3(m[3]);
    THRONG_TALLY(ops, 9, 9, 0, 0);
    const double r = radius_ * maxScaleFactor(m, ops);
    THRONG_TALLY(ops, 1, 0, 0, 0);
    out.radius_ = padded(out.center_, r, ops);
    if (!std::isfinite(out.radius_) || !std::isfinite(out.center_.x) || !std::isfinite(out.center_.y) ||
        !std::isfinite(out.center_.z))
        throw std::invalid_argument("BoundingSphere::transformed: argument 'm' is not finite or overflows");
    return out;
}

bool BoundingSphere::contains(const Vec3& point) const {
    if (!valid()) return false;
    const Vec3 d = point - center_;
    return glm::dot(d, d) <= radius_ * radius_;
}

bool BoundingSphere::contains(const BoundingSphere& sphere) const {
    if (!sphere.valid()) return true;
    if (!valid()) return false;
    return glm::length(sphere.center_ - center_) + sphere.radius_ <= radius_;
}

}  // namespace throng
