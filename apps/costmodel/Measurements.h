#pragma once
// Measurements of the real pipeline for the cost-model report: the example scene's operations
// counted by the pipeline's own counters, wall-clock time of both methods as scenes grow, and what
// the LOD scale trades between time and accuracy.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "KernelCosts.h"
#include "throng/actors/ActorFrameStatistics.h"
#include "throng/scenegraph/OpCategory.h"

namespace throng::costmodel {

/// Operation counts and FMULT of one frame, by category, read from an OpCounter.
struct CategoryFigures {
    std::array<std::uint64_t, kOpCategoryCount> operations{};  ///< NO_xx counts
    std::array<std::uint64_t, kOpCategoryCount> fmult{};       ///< FMULT
    std::array<OpTally, kOpCategoryCount> ops{};               ///< elementary operations behind the FMULT
};

/// The example scene (Tables 2-3) measured under both methods.
struct ExampleSceneFigures {
    CategoryFigures traditional;          ///< one frame, traditional processing
    CategoryFigures actor;                ///< the same frame, actor processing
    ActorFrameStatistics traditionalStats;///< its statistics
    ActorFrameStatistics actorStats;      ///< its statistics (the Table 2 classification)
    double averageCost = 0;               ///< measured CO_01a: FMULT of DOF values per Skeleton node (traditional)
    double refpointCost = 0;              ///< measured CO_02a per actor (traditional)
    double skeletonRootCost = 0;          ///< measured CO_03a per actor (traditional)
    double averageCostActor = 0;          ///< measured CO_01a per posed node under actor processing
    KernelFigures kernels;                ///< what the verified kernels predict (per-invocation costs, invocations)
};

/// One size of the wall-clock comparison.
struct WallClockRow {
    std::size_t actors = 0;           ///< actors in the scene (Table 2 proportions)
    std::size_t posed = 0;            ///< actors posed by actor processing
    double traditionalMs = 0;         ///< APP+CULL, median
    double actorMs = 0;               ///< APP+CULL, median
    double timeFactor = 0;            ///< traditional / actor time
    double fmultFactor = 0;           ///< traditional / actor FMULT, as counted
    double modelFactor = 0;           ///< Eq. 3 recomputed at the measured AverageCost, fTrack = fCoh = 1
    double publishedFactor = 0;       ///< Eq. 3 as published, same point
};

/// Actors of the accuracy sweep's town (walking seed humanoids over 400 m x 400 m).
inline constexpr std::size_t kAccuracyActors = 3000;

/// One LOD scale of the accuracy sweep.
struct AccuracyRow {
    double lodScale = 0;                 ///< distance multiplier (1 = as authored)
    double appCullMs = 0;                ///< APP+CULL, median
    double meanErrorMm = 0;              ///< mean joint-position error against full detail, millimetres
    double maxErrorMm = 0;               ///< largest joint-position error, millimetres
    double identicalShare = 0;           ///< share of full detail's draw list drawn identically
    std::uint64_t nodesEvaluated = 0;    ///< Skeleton nodes evaluated
    std::uint64_t primitives = 0;        ///< primitives drawn
};

/// Reports progress of long measurements (a line of text).
using Progress = std::function<void(const std::string&)>;

/// Builds the example scene and counts one frame under each method.
ExampleSceneFigures measureExampleScene();
/// Times both methods on scenes of Table 2's proportions of each size (skipping sizes that would
/// not fit in memory, with a message).
std::vector<WallClockRow> measureWallClock(const std::vector<std::size_t>& sizes, const Progress& progress);
/// Sweeps the LOD scale over a town-like crowd seen from the street; the first row is full detail
/// (the reference), then one row per scale.
std::vector<AccuracyRow> measureAccuracy(const std::vector<double>& scales, const Progress& progress);

}  // namespace throng::costmodel
