#pragma once
// A throng-town run on rank 0 (or alone): the world drawn frame by frame, headless or in a window,
// stats.csv written as it goes and summary.json at the end. Every frame is prepared (step, then APP
// and CULL) and drawn (DRAW, then its line of stats.csv); with --pipeline, DRAW of frame N overlaps
// the preparation of N+1. With --frame-budget the allocator picks each prepared frame's rung.

#include <chrono>
#include <cstdint>
#include <string>
#include <functional>
#include <memory>
#include <vector>

#include "CrowdRecording.h"
#include "FaceTally.h"
#include "TownOptions.h"
#include "TownRecords.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/render/GlContext.h"
#include "throng/render/ImpostorSet.h"
#include "throng/scenegraph/LineFile.h"
#include "throng/scenegraph/FramePipeline.h"
#include "throng/sim/FrameBudgetAllocator.h"
#include "throng/sim/Ranks.h"
#include "throng/sim/Simulation.h"

namespace throng::town {

class PosingRoot;

/// Message tag of the start signal rank 0 sends the other ranks when it is ready to step.
inline constexpr int kStartTag = 1;
/// Message tag of the navigation mesh rank 0 builds and sends the other ranks.
inline constexpr int kNavMeshTag = 2;
/// Message tag of rank 0's WorldKey, which the other ranks compare with their own before building.
inline constexpr int kWorldKeyTag = 3;

/// Rank 0's run of the town.
class TownRun {
public:
    /// Sets up drawing `world` as `o` asks (context, processor, impostors, renderer), opens stats.csv
    /// in o.out. `budget` and `recorder` may be null. Throws when the GL or a file cannot be made.
    TownRun(const TownOptions& o, sim::Simulation& world, sim::Ranks& ranks, std::unique_ptr<sim::FrameBudgetAllocator> budget,
            std::unique_ptr<CrowdRecording> recorder);
    ~TownRun();
    /// Whether the frames go to a window (else headless).
    bool windowed() const { return window_; }
    /// Runs o.frames frames headless: a PNG every o.every frames, a progress bar. Stops after the
    /// frame in progress when SIGINT or SIGTERM arrives (support::StopSignals).
    void runHeadless();
    /// Runs in the window until it closes, Esc, o.frames when --frames was given, or a stop signal.
    void runWindowed();
    /// Finishes the VTK files, writes summary.json (whole: "completed", and what stopped the run
    /// early: a signal or `error`) and says where the files are.
    void finish(const std::string& error = {});
    /// The signal that stopped the run before its frames were done, or 0.
    int stoppedBy() const { return stoppedBy_; }

private:
    void applyRung(int rung);
    void prepare(PreparedFrame& f, std::int64_t number, const Camera& camera, bool step, double cameraTime = 0.0);
    void draw(const PreparedFrame& f, const std::function<void()>& beforePresent);
    void allocate();
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

    const TownOptions& o_;
    sim::Simulation& world_;
    sim::Ranks& ranks_;
    std::unique_ptr<sim::FrameBudgetAllocator> budget_;
    std::unique_ptr<CrowdRecording> recorder_;
    bool distributed_ = false;
    std::shared_ptr<GlContext> context_;
    bool window_ = false;
    double lodScale_ = 1.0;
    double townLodScale_ = 0.0;  // the scene's; rungs may set their own
    double aspect_ = 1.0;
    std::unique_ptr<ActorProcessor> processor_;
    std::unique_ptr<ImpostorSet> impostors_;
    std::unique_ptr<CrowdRenderer> renderer_;
    std::unique_ptr<LineFile> csv_;  // stats.csv: whole lines, up to the last frame drawn
    int stoppedBy_ = 0;
    Sums sums_;
    std::chrono::steady_clock::time_point start_;
    double firstFrame_ = 0.0, lastFrameEnd_ = 0.0;
    double lastDrawMs_ = 0.0;  // the last frame's DRAW, for the window's text
    PreparedFrame prepared_[2];
    bool showOcclusion_ = false;  // the window's O key
    // --frame-budget: the rung of the next frame prepared (set between frames, on the main thread),
    // the rung the processor is set to, and the last frame drawn's rung and APP+CULL+DRAW.
    int nextRung_ = -1, appliedRung_ = -1, drawnRung_ = -1;
    double drawnCost_ = 0.0;
    std::vector<std::int64_t> rungFrames_;
    std::int64_t framesWithin_ = 0;
    bool caches_ = false;
    double hysteresis_ = 0.0;
    FramePipeline pipeline_;
    // Actors with a face layer (captions), and the face counts already put in a frame's row.
    struct FaceActor {
        ActorId id;
        sim::FaceLayer* layer;
        std::uint32_t slot;
    };
    std::vector<FaceActor> faceActors_;
    std::vector<char> drawnAsMesh_;  // per actor: 1 has a face, 2 and drawn as a mesh in the frame being captioned
    std::vector<Vec3> captionAt_;    // per actor: the top of its drawn parts (valid where drawnAsMesh_ is 2)
    FaceTally faces_;
    std::unique_ptr<PosingRoot> posing_;  // --pose-on-ranks under mpirun
    void placeCaptions(PreparedFrame& f, const Camera& camera);
};

}  // namespace throng::town
