// Internal to sim: Locomotion's exchanges between ranks (see RankExchange.h).

#include "RankExchange.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/Ranks.h"

namespace throng::sim::locomotion {
namespace {

// Message tags of a distributed step's four exchanges.
constexpr int kGhostTag = 101, kHandoverTag = 102, kWalkerTag = 103, kViewTag = 104;

// The view walkers are gathered near, as rank 0 sends it to the others each step.
struct GatherViewRecord {
    double planes[6][4] = {};   // (normal, offset) of each frustum plane, inside where n·p + d >= 0
    double margin = 0.0;        // metres a walker may stand outside and still be sent
    double shownMargin = 0.0;   // metres it may stand outside and still be seen (<= margin)
    std::uint32_t active = 0;   // planes in use (bit i: plane i)
    std::uint32_t on = 0;       // 0: send every walker
};

// Whether a walker standing at `p` is within `margin` of the view (always, with no view).
bool nearView(const GatherViewRecord& view, const glm::vec3& p, double margin) {
    if (!view.on) return true;
    for (int i = 0; i < 6; ++i) {
        if (!(view.active & (1u << i))) continue;
        const double* q = view.planes[i];
        if (q[0] * double(p.x) + q[1] * double(p.y) + q[2] * double(p.z) + q[3] < -margin) return false;
    }
    return true;
}

// What rank 0 holds of a walker standing at `p` (see RankExchange::present_).
std::uint8_t holding(const GatherViewRecord& view, const glm::vec3& p) {
    return nearView(view, p, view.shownMargin) ? 2 : nearView(view, p, view.margin) ? 1 : 0;
}

}  // namespace

RankExchange::RankExchange(Ranks& ranks, std::span<WalkerState> walkers, std::span<std::uint32_t> regionOf)
    : ranks_(ranks), state_(walkers), regionOf_(regionOf) {}

int RankExchange::rank() const { return ranks_.rank(); }

std::pair<std::uint32_t, std::uint32_t> RankExchange::assign(const RegionStepper& regions) {
    const std::uint32_t n = regions.count();
    // Consecutive regions per rank (a region's ghosts and handovers then arrive in the order of
    // their sending region, as in one process), split so that the most walkers any rank starts with
    // is as small as it can be (the linear partition: the least load for which filling ranks in
    // order fits every region, by bisection).
    const auto size = std::size_t(ranks_.size());
    auto fill = [&](std::size_t most, bool assign) {  // ranks used when none takes more than `most`
        std::size_t rank = 0, load = 0;
        for (std::uint32_t r = 0; r < n; ++r) {
            const std::size_t w = regions.region(r).owned.size();
            if (load > 0 && load + w > most && rank + 1 < size) ++rank, load = 0;
            load += w;
            if (assign) regionRank_[r] = int(rank);
        }
        return load <= most ? rank + 1 : size + 1;
    };
    std::size_t low = 0, high = state_.size();
    for (std::uint32_t r = 0; r < n; ++r) low = std::max(low, regions.region(r).owned.size());
    while (low < high) {
        const std::size_t mid = (low + high) / 2;
        if (fill(mid, false) <= size)
            high = mid;
        else
            low = mid + 1;
    }
    regionRank_.assign(n, 0);
    fill(low, true);
    const int me = ranks_.rank();
    firstRegion_ = std::uint32_t(std::lower_bound(regionRank_.begin(), regionRank_.end(), me) - regionRank_.begin());
    endRegion_ = std::uint32_t(std::upper_bound(regionRank_.begin(), regionRank_.end(), me) - regionRank_.begin());
    return {firstRegion_, endRegion_};
}

template <class Record>
std::uint64_t RankExchange::route(RegionStepper& regions, std::vector<Record> RegionStepper::Region::*list, std::uint32_t Record::*to,
                                  std::vector<Record> RegionStepper::Region::*into, int tag, const char* what) {
    for (std::uint32_t r = 0; r < regions.count(); ++r) (regions.region(r).*into).clear();
    // Every rank sends each other rank the records for its regions, in order of sending region;
    // each delivers what it received in order of sending rank, so of sending region.
    const auto size = std::size_t(ranks_.size());
    std::vector<std::vector<Record>> perRank(size);
    for (std::uint32_t r = firstRegion_; r < endRegion_; ++r)
        for (const Record& record : regions.region(r).*list) perRank[std::size_t(regionRank_[record.*to])].push_back(record);
    std::vector<Bytes> outgoing(size);
    for (std::size_t k = 0; k < size; ++k) outgoing[k] = packRecords(std::span<const Record>(perRank[k]));
    const std::size_t sentBefore = ranks_.bytesSent();
    const std::vector<Bytes> incoming = ranks_.exchange(outgoing, tag, what);
    for (std::size_t k = 0; k < size; ++k)
        for (const Record& record : unpackRecords<Record>(incoming[k], int(k), what)) {
            if (record.slot >= state_.size() || record.*to < firstRegion_ || record.*to >= endRegion_)
                throw RankError(int(k), "rank " + std::to_string(k) + " sent " + what + " for actor " + std::to_string(record.slot) +
                                            " in region " + std::to_string(record.*to) + ", which this rank does not step");
            (regions.region(record.*to).*into).push_back(record);
        }
    return ranks_.bytesSent() - sentBefore;
}

std::uint64_t RankExchange::routeGhosts(RegionStepper& regions) {
    return route(regions, &RegionStepper::Region::ghostsOut, &GhostRecord::region, &RegionStepper::Region::ghostsIn, kGhostTag,
                 "ghosts");
}

std::uint64_t RankExchange::routeHandovers(RegionStepper& regions) {
    return route(regions, &RegionStepper::Region::leaving, &HandoverRecord::to, &RegionStepper::Region::arriving, kHandoverTag,
                 "handovers");
}

RankExchange::Totals RankExchange::gather(Locomotion::RankStepRecord mine, std::span<const std::uint32_t> own,
                                          const std::optional<Frustum>& gatherView, double margin, double shownMargin) {
    // Rank 0 tells the others which walkers to send: those near the frame's view, or every one.
    GatherViewRecord view;
    if (ranks_.rank() == 0 && gatherView) {
        view.on = 1, view.margin = margin, view.shownMargin = std::min(shownMargin, margin), view.active = gatherView->activePlanes();
        for (int i = 0; i < 6; ++i)
            for (int k = 0; k < 4; ++k) view.planes[i][k] = gatherView->plane(i)[k];
    }
    {
        const Stopwatch wait;
        const Bytes bytes = ranks_.broadcast(packRecords(std::span<const GatherViewRecord>(&view, 1)), kViewTag, "view");
        const std::vector<GatherViewRecord> got = unpackRecords<GatherViewRecord>(bytes, 0, "the view");
        if (got.size() != 1) throw RankError(0, "rank 0 sent " + std::to_string(bytes.size()) + " bytes for the view, not one record");
        view = got[0];
        mine.waitMs += wait.elapsedMs();
    }
    if (posing_ && !view.on)
        throw std::logic_error("Locomotion: walkers posed where they are stepped need the view of every step (setGatherView on rank 0)");
    // One message per rank: its share of the step, then a record per walker it sends, those that
    // may be seen first (mine.shown of them), then those that only matter to them (whom they look
    // at), written in place (a million walkers are 40 MB a step: not copied twice).
    // Rank 0 draws: its own walkers are up to date there, it sends none (and counts them all as
    // sent). Posing where stepped, every rank poses its own walkers and needs the others' only as
    // whom they may look at: every rank sends every other its walkers near the view, or none when
    // nobody looks at anyone (no margin beyond the shown one).
    const bool root = ranks_.rank() == 0;
    const bool looked = view.margin > view.shownMargin;
    std::size_t sent = 0, shown = 0;
    held_.clear();
    if (!root || posing_)
        for (std::uint32_t slot : own) {
            const std::uint8_t h = holding(view, state_[slot].position);
            held_.push_back(h);
            sent += h != 0, shown += h == 2;
        }
    mine.sent = root && !posing_ ? own.size() : sent;
    mine.shown = root && !posing_ ? own.size() : shown;
    const std::size_t records = posing_ && !looked ? 0 : sent;
    Bytes message(sizeof(Locomotion::RankStepRecord) + records * sizeof(WalkerRecord));
    std::memcpy(message.data(), &mine, sizeof mine);
    std::size_t k = 0;
    for (const std::uint8_t pass : {std::uint8_t(2), std::uint8_t(1)})
        for (std::size_t i = 0; i < held_.size() && k < records; ++i) {
            if (held_[i] != pass) continue;
            const WalkerState& s = state_[own[i]];
            WalkerRecord w;
            w.slot = own[i], w.region = regionOf_[own[i]];
            for (int c = 0; c < 3; ++c) w.position[c] = s.position[c];
            w.heading = s.heading, w.speed = s.speed, w.runWeight = s.runWeight, w.phase = s.phase;
            std::memcpy(message.data() + sizeof(Locomotion::RankStepRecord) + k++ * sizeof(WalkerRecord), &w, sizeof w);
        }
    const std::size_t sentBefore = ranks_.bytesSent();
    const std::vector<Bytes> gathered =
        posing_ ? ranks_.allGather(message, kWalkerTag, "walkers") : ranks_.gather(message, kWalkerTag, "walkers");
    rankSteps_.assign(std::size_t(ranks_.size()), Locomotion::RankStepRecord{});
    Totals totals;
    if (!root && !posing_) {
        mine.stateBytes = ranks_.bytesSent() - sentBefore;
        rankSteps_[std::size_t(ranks_.rank())] = mine;
        return totals;
    }
    // Rank 0 (every rank, posing where stepped): with a view, the walkers near it are known, its
    // own as those the others sent; its own far from it are left out too, so that what rank 0
    // shows of the walkers depends on the view only, never on which rank steps whom. Posing where
    // stepped, a rank shows its own only: the others' are known, for its own to look at. Without
    // a view every walker is present.
    if (view.on) {
        present_.assign(state_.size(), 0);
        for (std::size_t i = 0; i < own.size(); ++i) present_[own[i]] = posing_ ? held_[i] : holding(view, state_[own[i]].position);
    } else {
        present_.clear();
    }
    const int me = ranks_.rank();
    for (std::size_t r = 0; r < gathered.size(); ++r) {
        const Bytes& bytes = gathered[r];
        if (bytes.size() < sizeof(Locomotion::RankStepRecord) ||
            (bytes.size() - sizeof(Locomotion::RankStepRecord)) % sizeof(WalkerRecord) != 0)
            throw RankError(int(r), "rank " + std::to_string(r) + " sent " + std::to_string(bytes.size()) +
                                        " bytes of walkers, not a step record and whole walker records");
        Locomotion::RankStepRecord& step = rankSteps_[r];
        std::memcpy(&step, bytes.data(), sizeof step);
        // What it sent: its message and its size header, to rank 0 or to every other rank.
        if (r > 0 || posing_) step.stateBytes = (bytes.size() + sizeof(std::uint64_t)) * (posing_ ? std::size_t(ranks_.size() - 1) : 1);
        totals.ghosts += step.ghosts, totals.handovers += step.handovers, totals.deferred += step.deferred;
        if (int(r) == me) continue;  // this rank's own walkers are already up to date
        const std::size_t n = (bytes.size() - sizeof(Locomotion::RankStepRecord)) / sizeof(WalkerRecord);
        if ((posing_ && !looked ? n != 0 : step.sent != n) || step.shown > step.sent)
            throw RankError(int(r), "rank " + std::to_string(r) + " sent " + std::to_string(n) + " walker records, saying " +
                                        std::to_string(step.sent) + " of which " + std::to_string(step.shown) + " may be seen");
        for (std::size_t i = 0; i < n; ++i) {
            WalkerRecord w;
            std::memcpy(&w, bytes.data() + sizeof(Locomotion::RankStepRecord) + i * sizeof(WalkerRecord), sizeof w);
            if (w.slot >= state_.size() || w.region >= regionRank_.size())
                throw RankError(int(r), "rank " + std::to_string(r) + " sent a walker record for actor " + std::to_string(w.slot) +
                                            " in region " + std::to_string(w.region) + ", which do not exist");
            WalkerState& s = state_[w.slot];
            regionOf_[w.slot] = w.region;
            s.position = glm::vec3(w.position[0], w.position[1], w.position[2]);
            s.heading = w.heading, s.speed = w.speed, s.runWeight = w.runWeight, s.phase = w.phase;
            if (view.on) present_[w.slot] = posing_ ? 1 : i < step.shown ? 2 : 1;
        }
    }
    presentCount_ = 0;
    shownSlots_.clear();
    for (std::uint32_t slot = 0; slot < present_.size(); ++slot) {
        presentCount_ += present_[slot] != 0;
        if (present_[slot] == 2) shownSlots_.push_back(slot);
    }
    shownCount_ = shownSlots_.size();
    return totals;
}

}  // namespace throng::sim::locomotion
