#pragma once
// Internal to sim: Locomotion across the ranks of an MPI run. The regions are split over the ranks
// (ranges of consecutive regions holding about as many starting walkers each); each step the ranks
// exchange ghosts and handovers for each other's regions, and rank 0 gathers the walkers' drawn
// state (WalkerRecord): every walker, or, given the view the frame culls against, only those near
// it. The same layout gives the same trajectories with any number of ranks.

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "RegionStepper.h"
#include "WalkerState.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/sim/Locomotion.h"

namespace throng::sim {
class Ranks;
}

namespace throng::sim::locomotion {

/// The exchanges of one rank of a distributed Locomotion.
class RankExchange {
public:
    /// What rank 0 learnt of the whole step from every rank (zeros elsewhere).
    struct Totals {
        std::size_t ghosts = 0;      ///< ghost records every rank exported
        std::size_t handovers = 0;   ///< agents every rank handed over
        std::size_t deferred = 0;    ///< walkers of far regions that did not step
    };

    /// The exchanges of this rank of `ranks`, for `walkers` owned by the regions `regionOf` says
    /// (all stay the caller's).
    RankExchange(Ranks& ranks, std::span<WalkerState> walkers, std::span<std::uint32_t> regionOf);

    /// Splits the regions of `regions` over the ranks (consecutive regions per rank, the most
    /// walkers any rank starts with as few as it can be). Returns this rank's [first, end).
    std::pair<std::uint32_t, std::uint32_t> assign(const RegionStepper& regions);
    /// This rank.
    int rank() const;
    /// The rank stepping region `r`.
    int rankOf(std::uint32_t r) const { return regionRank_[r]; }

    /// Empties every region's ghostsIn, then sends each rank the ghosts for its regions and takes
    /// in those for this rank's, in order of sending region. Returns the bytes sent.
    std::uint64_t routeGhosts(RegionStepper& regions);
    /// Empties every region's arriving, then does for handovers what routeGhosts does for ghosts.
    std::uint64_t routeHandovers(RegionStepper& regions);

    /// Makes every rank pose the walkers it steps (see Locomotion::setPosedWhereStepped): gather()
    /// then shows each rank its own walkers near the view, and lets it know the others' there.
    void setPosing(bool posing) { posing_ = posing; }
    /// Whether every rank poses the walkers it steps.
    bool posing() const { return posing_; }

    /// Sends rank 0 this rank's share of the step `mine` and the state of the walkers `own` it
    /// stepped; rank 0 sends the others `view` first (see Locomotion::setGatherView: only walkers
    /// within `margin` of it are sent, and those within `shownMargin` may be seen). On rank 0,
    /// takes in every rank's; returns rank 0's totals. Posing where stepped, every rank sends every
    /// other rank its walkers near the view (none when nobody looks at anyone) and takes in theirs,
    /// and every rank's totals are rank 0's; a step without a view is then a std::logic_error.
    Totals gather(Locomotion::RankStepRecord mine, std::span<const std::uint32_t> own, const std::optional<Frustum>& view,
                  double margin, double shownMargin);
    /// Whether rank 0 holds walker `slot`'s state of this step: near the view (whoever steps it),
    /// or any walker without a view.
    bool known(std::uint32_t slot) const { return present_.empty() || present_[slot] != 0; }
    /// Whether walker `slot` may be seen on rank 0 this step (known, and within the shown margin).
    bool shown(std::uint32_t slot) const { return present_.empty() || present_[slot] == 2; }
    /// Whether every walker may be seen (no view left any out).
    bool everyoneShown() const { return present_.empty(); }
    /// The walkers that may be seen on rank 0 this step, in increasing order of slot, or
    /// std::nullopt when no view left any out.
    std::optional<std::span<const std::uint32_t>> shownSlots() const {
        if (present_.empty()) return std::nullopt;
        return std::span<const std::uint32_t>(shownSlots_);
    }
    /// Walkers known on rank 0 this step, or `all` when no view left any out.
    std::size_t presentCount(std::size_t all) const { return present_.empty() ? all : presentCount_; }
    /// Walkers that may be seen on rank 0 this step, or `all` when no view left any out.
    std::size_t shownCount(std::size_t all) const { return present_.empty() ? all : shownCount_; }
    /// Each rank's share of the last step (see Locomotion::rankSteps).
    std::span<const Locomotion::RankStepRecord> rankSteps() const { return rankSteps_; }

private:
    template <class Record>
    std::uint64_t route(RegionStepper& regions, std::vector<Record> RegionStepper::Region::*list, std::uint32_t Record::*to,
                        std::vector<Record> RegionStepper::Region::*into, int tag, const char* what);

    Ranks& ranks_;
    std::span<WalkerState> state_;
    std::span<std::uint32_t> regionOf_;
    std::uint32_t firstRegion_ = 0, endRegion_ = 0;
    std::vector<int> regionRank_;
    std::vector<Locomotion::RankStepRecord> rankSteps_;
    // On rank 0, what it holds of each walker this step: 0 nothing, 1 its state (it matters to
    // someone who may be seen), 2 its state and it may be seen (empty: every walker, seen).
    std::vector<std::uint8_t> present_;
    std::size_t presentCount_ = 0, shownCount_ = 0;
    std::vector<std::uint32_t> shownSlots_;  // rank 0, with a view: the slots with present_ 2, increasing
    std::vector<std::uint8_t> held_;  // on the other ranks: what rank 0 holds of each walker sent
    bool posing_ = false;             // every rank poses its own walkers (and holds present_)
};

}  // namespace throng::sim::locomotion
