#pragma once
// Closed-form Reference Point motion shared by behaviours: standing, or walking a circle facing
// along it. Being a function of time, it never drifts however long the run.

#include <span>

#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

/// A Reference Point that stands at `center` facing `heading`, or, with radius > 0, walks a circle
/// round `center` at `speed`, starting at angle `heading`.
struct RefpointPath {
    Vec3 center{0.0};      ///< position, or centre of the circle (parent frame)
    double heading = 0.0;  ///< facing (radians about +Y), or starting angle on the circle
    double radius = 0.0;   ///< circle radius, metres (0: standing)
    double speed = 0.0;    ///< metres per second along the circle

    /// The Reference Point's matrix at `time` (local +Z faces the walking direction).
    Mat4 at(double time, OpTally* ops = nullptr) const;
    /// out[k] = paths[k].at(time, ops), the same bits, for every path, their sines and cosines
    /// taken together (detail::sinCos). Throws std::invalid_argument if `out` is shorter.
    static void atEach(std::span<const RefpointPath> paths, double time, std::span<Mat4> out, OpTally* ops = nullptr);
};

}  // namespace throng
