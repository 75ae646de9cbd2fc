#pragma once
// Cameras the tests and benchmarks set up: a perspective camera at an eye looking at a target, in
// one call, so a test states only what matters to it (where it looks from, and the lens).

#include "throng/scenegraph/Camera.h"

namespace throng::testkit {

/// The lens of a test camera: vertical field of view (radians), aspect, near and far planes.
struct Lens {
    double fovY = 1.0;    ///< radians
    double aspect = 1.5;  ///< width over height
    double near = 0.1;    ///< metres
    double far = 1000.0;  ///< metres
};

/// A perspective camera at `eye` looking at `target`, +Y up, through `lens`.
Camera lookingAt(const Vec3& eye, const Vec3& target, const Lens& lens = {});

}  // namespace throng::testkit
