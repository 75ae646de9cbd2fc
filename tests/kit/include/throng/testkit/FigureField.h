#pragma once
// A generic scene for demos, tests and benchmarks: animated figures walking in circles on a square
// field, each a Transform -> LOD (5 limbs + body / body / card) -> Geometry, 14 nodes per figure.

#include <memory>

#include "throng/scenegraph/Group.h"

namespace throng::testkit {

/// Builds `figures` animated figures 8 m apart on a square grid (x, z >= 0, Y up).
std::shared_ptr<Group> buildFigureField(int figures);
/// Side length in metres of the field built for `figures` figures.
double figureFieldExtent(int figures);

}  // namespace throng::testkit
