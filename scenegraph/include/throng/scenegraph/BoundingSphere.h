#pragma once
// A bounding sphere in double precision. Merging is robust (one sphere inside the other, coincident
// centres, zero radii) and always conservative: the result contains both inputs even after rounding.
// The class is a template over its scalar only so that tests can run the very same merge and
// transform code on an operation-counting number type; everything else uses BoundingSphere.

#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

/// A sphere (centre, radius) over scalar `S`. A default-constructed sphere is empty (invalid) and
/// merges as nothing. Its operations are defined in detail/BoundingSphereImpl.h and compiled for
/// double in the library.
template <class S>
class BasicBoundingSphere {
public:
    /// The centre's type.
    using Vec = glm::vec<3, S, glm::defaultp>;
    /// The type of the matrices a sphere is transformed by.
    using Mat = glm::mat<4, 4, S, glm::defaultp>;

    /// An empty sphere: valid() is false and it contains nothing.
    BasicBoundingSphere() = default;
    /// A sphere; throws std::invalid_argument if `center` or `radius` is not finite or radius < 0.
    BasicBoundingSphere(const Vec& center, S radius);
    /// The same sphere in another scalar type (a conversion, no arithmetic).
    template <class U>
    explicit BasicBoundingSphere(const BasicBoundingSphere<U>& other)
        : center_(other.center()), radius_(static_cast<S>(other.radius())) {}

    /// Whether the sphere holds anything (an empty sphere has a negative radius). One comparison.
    bool valid() const { return radius_ >= S(0); }
    /// The centre.
    const Vec& center() const { return center_; }
    /// The radius (negative when empty).
    S radius() const { return radius_; }

    /// Grows to enclose `point` (throws if it is not finite). Costs are added to `ops` if non-null.
    void expandBy(const Vec& point, OpTally* ops = nullptr);
    /// Grows to enclose `sphere` with the smallest sphere holding both; empty spheres are ignored.
    void expandBy(const BasicBoundingSphere& sphere, OpTally* ops = nullptr);
    /// Grows the radius by `margin` metres (throws if negative or not finite).
    void inflate(S margin);

    /// The sphere enclosing this one after the affine part of `m` (rotation, any scale, shear,
    /// translation). The radius bound is exact for rotation-and-scale matrices and never too small.
    BasicBoundingSphere transformed(const Mat& m, OpTally* ops = nullptr) const;

    /// Whether `point` lies inside or on the sphere.
    bool contains(const Vec& point) const;
    /// Whether `sphere` lies entirely inside this one (an empty sphere is inside anything).
    bool contains(const BasicBoundingSphere& sphere) const;
    /// A cheap sufficient test (no square root) that expandBy(`sphere`) would leave this sphere
    /// unchanged: `sphere` lies inside with a margin that rounding cannot eat. False when unsure.
    bool clearlyContains(const BasicBoundingSphere& sphere) const {
        // The margin (r <= R / 2, squared distance a millionth short of (R - r)^2) is far beyond
        // the few ulps by which expandBy's own sum dist + r may round up: it returns early too.
        if (!sphere.valid() || !valid() || !(sphere.radius_ <= S(0.5) * radius_)) return false;
        const Vec d = sphere.center_ - center_;
        const S room = radius_ - sphere.radius_;
        return glm::dot(d, d) <= room * room * S(0.999999);
    }

    /// Exact equality of centre and radius, for tests.
    bool operator==(const BasicBoundingSphere&) const = default;

private:
    Vec center_{S(0)};
    S radius_ = S(-1);
};

/// The bounding sphere of the scenegraph (double precision).
using BoundingSphere = BasicBoundingSphere<double>;
extern template class BasicBoundingSphere<double>;

/// Upper bound of the largest factor by which the linear part of `m` stretches a vector (its
/// spectral norm): exact when the columns are orthogonal, conservative with shear.
double maxScaleFactor(const Mat4& m, OpTally* ops = nullptr);

}  // namespace throng
