#pragma once
// A bounding sphere in double precision. Merging is robust (one sphere inside the other, coincident
// centres, zero radii) and always conservative: the result contains both inputs even after rounding.

#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

/// A sphere (centre, radius). A default-constructed sphere is empty (invalid) and merges as nothing.
class BoundingSphere {
public:
    /// An empty sphere: valid() is false and it contains nothing.
    BoundingSphere() = default;
    /// A sphere; throws std::invalid_argument if `center` or `radius` is not finite or radius < 0.
    BoundingSphere(const Vec3& center, double radius);

    /// Whether the sphere holds anything (an empty sphere has a negative radius).
    bool valid() const { return radius_ >= 0.0; }
    /// The centre.
    const Vec3& center() const { return center_; }
    /// The radius (negative when empty).
    double radius() const { return radius_; }

    /// Grows to enclose `point` (throws if it is not finite). Costs are added to `ops` if non-null.
    void expandBy(const Vec3& point, OpTally* ops = nullptr);
    /// Grows to enclose `sphere` with the smallest sphere holding both; empty spheres are ignored.
    void expandBy(const BoundingSphere& sphere, OpTally* ops = nullptr);
    /// Grows the radius by `margin` metres (throws if negative or not finite).
    void inflate(double margin);

    /// The sphere enclosing this one after the affine part of `m` (rotation, any scale, shear,
    /// translation). The radius bound is exact for rotation-and-scale matrices and never too small.
    BoundingSphere transformed(const Mat4& m, OpTally* ops = nullptr) const;

    /// Whether `point` lies inside or on the sphere.
    bool contains(const Vec3& point) const;
    /// Whether `sphere` lies entirely inside this one (an empty sphere is inside anything).
    bool contains(const BoundingSphere& sphere) const;

    /// Exact equality of centre and radius, for tests.
    bool operator==(const BoundingSphere&) const = default;

private:
    Vec3 center_{0.0};
    double radius_ = -1.0;
};

/// Upper bound of the largest factor by which the linear part of `m` stretches a vector (its
/// spectral norm): exact when the columns are orthogonal, conservative with shear.
double maxScaleFactor(const Mat4& m, OpTally* ops = nullptr);

}  // namespace throng
