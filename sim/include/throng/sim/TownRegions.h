#pragma once
// The regions of a town (rectangles of city blocks, as its scene declares them) as a RegionGrid.

#include <string>

#include "throng/sim/RegionGrid.h"
#include "throng/sim/SceneDescription.h"

namespace throng::sim {

/// The regions of `town` over its blocks (each block of `blockTiles` + 1 tiles, the town centred
/// on the origin). Throws SceneError (file `file`, path under /town/regions) if a rectangle
/// reaches outside the town, overlaps another, or a block is in none.
RegionGrid townRegions(const TownDescription& town, const std::string& file);

}  // namespace throng::sim
