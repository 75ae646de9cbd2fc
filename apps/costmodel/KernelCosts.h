#pragma once
// What the verified kernels predict for the example scene: the FMULT (and elementary operations)
// of one invocation of each counted kernel on the scene's own data, read from the kernels' tallies
// (test_counted_ops checks every tally against the operations the kernel executes), and the
// number of invocations the cascade calls for, read from the scene and the frame's statistics
// (never from the operation counters). check_costmodel.py multiplies the two and compares the
// result with what the pipeline counted, category by category.

#include <cstdint>
#include <map>
#include <string>

#include "throng/actors/ActorFrameStatistics.h"
#include "throng/actors/Crowd.h"
#include "throng/research/CostModelScene.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/OpTally.h"

namespace throng::costmodel {

/// Per-invocation costs of the kernels and the counts of invocations, per method.
struct KernelFigures {
    std::map<std::string, OpTally> kernels;         ///< kernel -> operations of one invocation
    std::map<std::string, double> traditional;      ///< structural counts under traditional processing
    std::map<std::string, double> actor;            ///< structural counts under actor processing
};

/// How the processor that measured the scene was set up (ActorProcessor's defaults).
struct ProcessorSettings {
    double lodScale = 1.0;        ///< distance multiplier
    bool skeletalLod = true;      ///< skeletal LOD on
    bool behaviouralLod = true;   ///< behavioural LOD on
};

/// Measures the kernels on the example scene after a processor set up as `settings` has processed
/// its frame under actor processing (`actorStats`, `actorDrawList`); `traditionalStats` is the same
/// frame under traditional processing. Throws std::runtime_error if a kernel's cost is not the same
/// for every actor (the scene is built so that it is, and check_costmodel.py relies on it).
KernelFigures measureKernels(const CostModelScene& scene, const Crowd& crowd, const ProcessorSettings& settings,
                             const DrawList& actorDrawList, const ActorFrameStatistics& traditionalStats,
                             const ActorFrameStatistics& actorStats);

}  // namespace throng::costmodel
