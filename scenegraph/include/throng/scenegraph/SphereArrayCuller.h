#pragma once
// Frustum classification of many spheres stored as flat float arrays (structure of arrays), the way
// Filament culls: no pointers, no branches per plane, several spheres per SIMD instruction.
// Coordinates are relative to an origin (normally the eye), so float keeps its precision far from
// the world origin; a rounding margin keeps the answer conservative with respect to double maths.

#include <array>
#include <cstddef>
#include <span>

#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpTally.h"
#include "throng/scenegraph/detail/SphereArrayKernel.h"

namespace throng {

/// Spheres as four parallel arrays of equal length, relative to the culler's origin.
struct SphereArrays {
    std::span<const float> x;       ///< centre x minus origin x
    std::span<const float> y;       ///< centre y minus origin y
    std::span<const float> z;       ///< centre z minus origin z
    std::span<const float> radius;  ///< radius (>= 0)
};

/// Classifies spheres in flat arrays against one frustum.
class SphereArrayCuller {
public:
    /// Prepares the planes of `frustum` relative to `origin` (for example the camera's eye).
    SphereArrayCuller(const Frustum& frustum, const Vec3& origin);

    /// Writes the Containment of sphere i to out[i]. Outside and Inside are only reported when they
    /// hold for the exact (double) sphere too; otherwise the answer is Intersects. Throws
    /// std::invalid_argument if the arrays differ in length or `out` is shorter.
    void classify(const SphereArrays& spheres, std::span<Containment> out, OpTally* ops = nullptr) const;

    /// Operations spent per sphere (the kernel does the same work for every sphere, with no branch):
    /// reach 1 mult 4 adds, six signed distances 18 mults 18 adds, twice six margins, five minimums
    /// and the reach 24 adds, two comparisons 2 adds.
    static constexpr OpTally kOpsPerSphere{19, 48, 0, 0, 0};

    /// The origin the sphere coordinates are relative to.
    const Vec3& origin() const { return origin_; }
    /// The planes as the kernel uses them, relative to the origin (inactive planes always inside).
    const detail::CullPlanes<float>& planes() const { return planes_; }

private:
    Vec3 origin_;
    detail::CullPlanes<float> planes_;
};

}  // namespace throng
