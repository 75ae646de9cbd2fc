#pragma once
// Per-frame statistics of a processing method: time per phase and the work each phase did.

#include <cstdint>

#include "throng/scenegraph/CullVisitor.h"
#include "throng/scenegraph/MatrixBoundsVisitor.h"
#include "throng/scenegraph/OcclusionCulling.h"

namespace throng {

/// What one frame cost and produced.
struct FrameStatistics {
    std::uint64_t frame = 0;            ///< frame number
    double appMs = 0;                   ///< APP: behaviours and update callbacks
    double matricesBoundsMs = 0;        ///< matrices composed and bounds recomputed
    double cullMs = 0;                  ///< CULL
    double drawMs = 0;                  ///< DRAW (the backend's time)
    std::uint64_t callbacksRun = 0;     ///< update callbacks run
    MatrixBoundsStatistics matrices;    ///< matrix and bound work
    CullStatistics cull;                ///< culling work and results
    OcclusionStatistics occlusion;      ///< the occlusion stage (zero when occlusion culling is off)
    std::uint64_t fmultTotal = 0;       ///< FMULT counted this frame (0 when counting is off)
};

}  // namespace throng
