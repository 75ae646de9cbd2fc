#pragma once
// throng-town with --pose-on-ranks: every rank poses the walkers it steps and sends rank 0 draw
// records, not walker state, so that rank 0's APP and CULL grow with its own share of the view.
// Each frame rank 0 sends its orders (the camera's time, the LOD and tier settings of the frame,
// its occlusion buffer) once its occlusion stage is done, the ranks run APP and CULL for their own
// walkers against them, the key-pose caches are settled over every rank (RankKeyPoseArbiter), and
// rank 0 merges every rank's records and statistics into the frame it draws: the frame one process
// holding every actor would have drawn. A walker's impostor and key-pose tiers travel with it
// from rank to rank (Locomotion::carried).

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "FaceTally.h"
#include "TownOptions.h"
#include "TownRecords.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/DrawRecords.h"
#include "throng/sim/RankKeyPoseArbiter.h"
#include "throng/sim/Ranks.h"
#include "throng/sim/Simulation.h"

namespace throng::town {

/// Message tag of each frame's orders, rank 0 to the others.
inline constexpr int kFrameOrderTag = 4;
/// Message tag of each rank's share of a frame (statistics, face counts, draw records), to rank 0.
inline constexpr int kShareTag = 5;
/// Message tags of the key-pose caches' arbiter (this and the next).
inline constexpr int kKeyPoseTag = 6;

/// The walkers a process poses carry their impostor and key-pose tiers with them: before APP and
/// CULL each walker it shows takes the tiers it carries, afterwards it carries them on.
class WalkerTiers {
public:
    /// For the walkers of `world` (none when nothing walks).
    explicit WalkerTiers(sim::Simulation& world);
    /// Before a frame's APP and CULL: `processor` takes the tiers of the walkers it shows.
    void take(ActorProcessor& processor) const;
    /// After it: those walkers carry their tiers on.
    void keep(const ActorProcessor& processor);

private:
    sim::Locomotion* walkers_ = nullptr;
    std::span<const ActorId> actorOfSlot_;
};

/// Rank 0's side: the frame's orders sent from within its APP and CULL, the shares merged after.
class PosingRoot {
public:
    /// Sets `processor` (rank 0's, with its impostors and caches attached) up to pose its share of
    /// `world` among `ranks`: its key-pose caches settled over every rank, its occlusion stage
    /// resting by the counts of every share, the orders sent before its CULL.
    PosingRoot(sim::Simulation& world, sim::Ranks& ranks, ActorProcessor& processor, double aspect);
    /// What the other ranks draw with (sent with the start signal): whether key-pose caches are
    /// attached, and each template's impostor, as numbers and bounds.
    sim::Bytes setup() const;
    /// Before APP and CULL of frame `number`, whose camera is the path's at `cameraTime`.
    void beginFrame(std::int64_t number, double cameraTime);
    /// After APP and CULL: every rank's share of frame `f` (its stats rank 0's so far) gathered;
    /// f.list becomes f.merged, rank 0's items of the scene then every rank's actors', and f.stats
    /// and the face counts the whole frame's. Throws sim::RankError naming a rank whose share
    /// cannot be read.
    void finishFrame(PreparedFrame& f, const FaceTally::Counts& mine);

private:
    void sendOrders(const OcclusionBuffer* buffer);

    sim::Simulation& world_;
    sim::Ranks& ranks_;
    ActorProcessor& processor_;
    double aspect_;
    sim::RankKeyPoseArbiter arbiter_;
    DrawReferences refs_;
    DrawRecordMerger merger_;
    WalkerTiers tiers_;
    std::int64_t number_ = 0;
    std::size_t bytesBefore_ = 0;  // Ranks::bytesSent when the frame began
    double cameraTime_ = 0.0;
    sim::Bytes orders_, mine_;
    std::vector<std::span<const std::byte>> messages_;
};

/// A rank other than 0 of a run whose ranks pose their own walkers: waits for rank 0's set-up,
/// then, frame after frame, steps, takes rank 0's orders, runs APP and CULL for its own walkers and
/// sends rank 0 its share. A failure stops every rank. Returns the exit code.
int poseShare(sim::Simulation& world, sim::Ranks& ranks, const TownOptions& o);

}  // namespace throng::town
