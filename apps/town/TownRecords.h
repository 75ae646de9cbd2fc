#pragma once
// What a throng-town run records: one frame between its APP/CULL and its DRAW (PreparedFrame), its
// line of stats.csv, the running sums summary.json reports as means, and summary.json itself.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "TownOptions.h"
#include "throng/actors/ActorFrameStatistics.h"
#include "throng/render/Caption.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Image.h"
#include "throng/sim/FrameBudgetAllocator.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/Simulation.h"

namespace throng::town {

/// One frame between its APP/CULL and its DRAW: what DRAW and the statistics need of it.
struct PreparedFrame {
    std::int64_t number = 0;           // frame number
    double time = 0.0;                 // simulation time
    double stepMs = 0.0;               // the simulation step
    std::uint64_t ghosts = 0;          // walkers seen across a region border in that step
    std::uint64_t handovers = 0;       // walkers handed to another region at its end
    std::uint64_t deferred = 0;        // walkers of far regions that did not step (a declared approximation)
    Camera camera;                     // the camera it was culled for
    ActorFrameStatistics stats;        // APP and CULL
    const DrawList* list = nullptr;    // its draw list (the processor keeps it through the next frame, or `merged`)
    DrawList merged;                   // --pose-on-ranks: rank 0's items of the scene, then every rank's actors
    Image occlusion;                   // its occlusion buffer as a picture, when the window shows it
    std::vector<sim::Locomotion::RankStepRecord> ranks;  // each rank's share of the step, when distributed
    /// --pose-on-ranks: what one rank posed of the frame.
    struct PosedShare {
        std::uint64_t items = 0;        // draw items of its actors
        std::uint64_t bytesSent = 0;    // bytes it sent other ranks for posing: draw records and key-pose demands
                                        // (rank 0: frame orders and key-pose rows), payloads and size headers
        double appCullMs = 0.0;         // its APP and CULL
        double waitMs = 0.0;            // of which waiting in the key-pose caches' exchanges
    };
    std::vector<PosedShare> posed;     // --pose-on-ranks: each rank's, indexed by rank
    int rung = -1;                     // --frame-budget: the ladder rung it was processed and drawn with
    std::uint64_t faceEvaluations[3] = {0, 0, 0};  // actors whose expression, blink, phrase was evaluated in its CULL
    double faceMs = 0.0;               // the face layers' time in its CULL (all threads)
    std::vector<Caption> captions;     // what near speakers say, shown above their heads
};

/// The header line of stats.csv: the frame's columns, the allocator's with --frame-budget, then each
/// rank's share of the step when `ranks` > 0 (and of the frame's posing, with `posing`).
std::string csvHeader(int ranks, bool budget, bool posing = false);
/// The stats.csv line of frame `f`, drawn in `drawMs` (`frameMs` since the previous frame's end).
std::string csvRow(const PreparedFrame& f, double drawMs, double frameMs, const CrowdRenderStatistics& r,
                   const sim::FrameBudgetAllocator* budget);

/// Running sums of what summary.json reports as means.
struct Sums {
    double app = 0, phases[9] = {}, draw = 0, step = 0;
    double drawCpu = 0, drawGpu = 0;  // DRAW's CPU side, and its GPU time over the gpuFrames that have it
    std::int64_t gpuFrames = 0;
    double posed = 0, nodes = 0, items = 0, primitives = 0, impostors = 0;
    double faceEvaluations = 0, faceMs = 0, morphTargetsRead = 0, captions = 0;
    std::vector<sim::Locomotion::RankStepRecord> ranks;  // distributed: each rank's share, summed
    std::vector<PreparedFrame::PosedShare> posedShares;  // --pose-on-ranks: each rank's posing, summed
    std::int64_t frames = 0;
    /// Adds frame `f`, drawn in `drawMs` with the renderer's statistics `r`.
    void add(const PreparedFrame& f, double drawMs, const CrowdRenderStatistics& r);
};

/// summary.json of a run: the options, the world, the means of `sums`, the wall time.
nlohmann::json summaryJson(const TownOptions& o, const sim::Simulation& world, const Sums& sums, double wallSeconds,
                           double firstFrameSeconds, int ranks);

}  // namespace throng::town
