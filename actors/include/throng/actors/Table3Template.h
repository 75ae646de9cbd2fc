#pragma once
// The synthetic actor of the cost model's example scene (seed 002 Table 3): 40 Skeleton nodes with
// 2 DOFs each, 80 internal bounding spheres (a geometry sphere and a subtree sphere per node) and
// 41 LOD nodes (one per Skeleton node and one for the actor). Skeletal LOD deactivates half of the
// nodes beyond `halfDistance` (the model's fLODtopo = 0.5). Its clip "sway" moves every DOF and
// carries the Skeleton Root round a circle of `rootCircle` metres about the Reference Point.

#include <memory>

#include "throng/actors/ActorTemplate.h"

namespace throng {

/// Shape of the Table 3 actor.
struct Table3Options {
    double halfDistance = 50.0;   ///< beyond it, the 20 distal nodes are deactivated
    double farDistance = 1000.0;  ///< the Skeleton nodes' geometry ends here; the actor-level piece takes over
    double rootCircle = 2.0;      ///< radius of the Skeleton Root's circle about the Reference Point
};

/// Builds the Table 3 template: a 4-node spine and four 9-node limbs.
std::shared_ptr<const ActorTemplate> makeTable3Template(const Table3Options& options = {});

}  // namespace throng
