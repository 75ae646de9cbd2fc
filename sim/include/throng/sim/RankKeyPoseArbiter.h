#pragma once
// Key-pose caches settled across the ranks of a run (KeyPoseArbiter over sim::Ranks): each rank's
// demands go to rank 0, which selects for their sum; every rank then copies rank 0's rows.

#include <utility>
#include <vector>

#include "throng/actors/KeyPoseArbiter.h"

namespace throng::sim {

class Ranks;

/// The arbiter of one rank of a run whose ranks each pose some actors of one crowd.
class RankKeyPoseArbiter : public KeyPoseArbiter {
public:
    /// Settles over `ranks` (which must outlive the arbiter), with message tag `tag` and `tag` + 1.
    RankKeyPoseArbiter(Ranks& ranks, int tag);
    /// Collective: every rank's processor calls it at the same point of every frame (see
    /// KeyPoseArbiter). Throws RankError naming a rank whose demands do not fit the caches (another
    /// number of caches, a pose out of range, out of order), or rank 0 when its rows do not.
    KeyPoseSelectionCounts settle(std::span<const std::vector<KeyPoseDemand>> demands,
                                  std::span<const std::shared_ptr<KeyPoseCache>> caches, std::uint64_t frame) override;

    /// Milliseconds settle() spent in its exchanges since the last call: on rank 0 mostly waiting
    /// for the slowest rank to reach its CULL 2, elsewhere for rank 0's selection.
    double takeWaitMs() { return std::exchange(waitMs_, 0.0); }

private:
    Ranks& ranks_;
    double waitMs_ = 0.0;
    int tag_;
    KeyPoseSelector selector_;
    std::vector<KeyPoseDemand> sum_, part_;  // rank 0: one cache's demands added, and one rank's
    std::vector<std::uint32_t> rowPoses_;     // the other ranks: one cache's rows as rank 0 sent them
};

}  // namespace throng::sim
