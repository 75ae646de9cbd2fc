#pragma once
// Seed 004's Figure 12 as reusable parts: the schedule of the clips a crowd may choose from (all of
// them, then one, then one more every phase), the rule by which actors choose again when the set
// changes, a behaviour whose actors stand still playing the clip they chose (changeable between
// frames, which KeyframeBehaviour's actors are not), and the per-phase summary of what a key-pose
// cache did frame by frame. bench_keypose_timeline runs them; tests/harness tests them.

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "throng/actors/Behaviour.h"

namespace throng {
class ActorTemplate;
}

namespace throng::bench {

/// Which clips are available when (seed 004 §5, Fig. 12): phase 0 offers all `clips`; phase k
/// (1 <= k <= clips) offers the first k of them. Each phase lasts `phaseSeconds`, so the paper's
/// five clips and 5 s give 0-5 s all five, 5-10 s one, ..., 25-30 s all five again.
struct ClipSchedule {
    std::uint32_t clips = 5;     ///< clips in the schedule's order (>= 1)
    double phaseSeconds = 5.0;   ///< length of a phase (> 0)

    /// Number of phases: clips + 1.
    std::uint32_t phases() const { return clips + 1; }
    /// Seconds the whole schedule lasts.
    double duration() const { return phases() * phaseSeconds; }
    /// Phase at `time` (seconds from 0; a time within 1e-9 of a phase's start counts as in it, so a
    /// frame that lands on a boundary by floating-point division is in the new phase). Times
    /// beyond the schedule stay in its last phase; negative times are in phase 0.
    std::uint32_t phaseAt(double time) const;
    /// Clips offered in `phase`: all of them in phase 0, else the first `phase`.
    std::uint32_t available(std::uint32_t phase) const { return phase == 0 ? clips : phase; }
};

/// What one actor plays: a clip of the schedule (its index in the schedule's order) and the offset
/// added to the frame time to get its clip time.
struct ClipChoice {
    std::uint32_t clip = 0;   ///< index into the schedule's clips
    double offset = 0.0;      ///< seconds, in [0, duration of the clip)
};

/// Uniform numbers in [0, 1) from a std::mt19937_64's top 53 bits: the same draws on every
/// platform (std::uniform_real_distribution's are not specified).
class UnitRandom {
public:
    /// A stream seeded with `seed`.
    explicit UnitRandom(std::uint64_t seed) : engine_(seed) {}
    /// The next number, in [0, 1).
    double next() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

private:
    std::mt19937_64 engine_;
};

/// The re-pick rule at a phase boundary (and at the start, with `share` 1): an actor whose clip is
/// no longer among the first `available` always chooses again; any other actor chooses again with
/// probability `share`. Choosing is a clip drawn uniformly among the available ones and an offset
/// drawn uniformly within that clip's duration (`durations`, seconds, one per schedule clip), so
/// actors do not play in lock-step. Every actor consumes three draws whatever happens, so one
/// actor's fate never shifts another's. Returns how many actors chose again. Throws
/// std::invalid_argument if `available` is 0 or exceeds durations.size(), a duration is not
/// positive and finite, or `share` is outside [0, 1].
std::size_t chooseClips(std::span<ClipChoice> choices, std::uint32_t available, std::span<const double> durations, double share,
                        UnitRandom& random);

/// Actors standing still (each at its own place and heading), each playing, looped, the clip of the
/// template it chose: a ClipChoice that may change between frames (setChoice), which
/// KeyframeBehaviour's fixed clip cannot. One behaviour level (full detail at any distance), the
/// Skeleton Root sampled from the clip like KeyframeBehaviour's. mainClip() and clipTime() name the
/// template's clip and time, so a key-pose cache serves these actors as any others.
class ClipChoiceBehaviour final : public Behaviour {
public:
    /// Actors of `tmpl` choosing among its clips `clips` (template clip indices, in the schedule's
    /// order). Throws std::invalid_argument if the template is null, `clips` is empty, names a clip
    /// the template lacks, or a clip has no positive duration.
    ClipChoiceBehaviour(std::shared_ptr<const ActorTemplate> tmpl, std::vector<int> clips);

    /// Registers an actor at `position` facing `heading` (radians about +Y) playing `choice`;
    /// returns its slot. Throws std::invalid_argument for a non-finite value or a bad choice.
    std::uint32_t addActor(const Vec3& position, double heading, const ClipChoice& choice);
    /// Changes what actor `slot` plays from the next frame on. Throws std::invalid_argument for a
    /// bad slot, a clip outside the schedule or a non-finite offset.
    void setChoice(std::uint32_t slot, const ClipChoice& choice);
    /// What actor `slot` plays.
    const ClipChoice& choice(std::uint32_t slot) const { return choices_[slot]; }
    /// Every actor's choice, by slot (for chooseClips; call setChoice, or assign through
    /// choices(), only between frames).
    std::span<ClipChoice> choices() { return choices_; }
    /// Seconds each schedule clip lasts, in the schedule's order.
    std::span<const double> durations() const { return durations_; }

    std::span<const double> levelEnds() const override { return levelEnds_; }
    Mat4 referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) override;
    RootPose skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) override;
    void pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl, std::span<const std::uint8_t> active,
              std::span<float> dofs, OpTally* ops) override;
    /// The union of the Skeleton Root's places over every schedule clip: valid whatever the actor
    /// chooses later (Crowd::add reads it once).
    BoundingSphere skeletonRootExtent(std::uint32_t slot) const override;
    bool posesFromTemplateClips() const override { return true; }
    int mainClip(std::uint32_t slot) const override { return clips_[choices_[slot].clip]; }
    double clipTime(std::uint32_t slot, double time) const override { return time + choices_[slot].offset; }
    std::size_t bytesPerSlot() const override { return sizeof(ClipChoice) + sizeof(Vec3) + sizeof(double); }

private:
    void check(const ClipChoice& choice, const char* where) const;

    std::shared_ptr<const ActorTemplate> tmpl_;
    std::vector<int> clips_;           // template clip of each schedule clip
    std::vector<double> durations_;    // per schedule clip
    std::vector<double> levelEnds_;
    BoundingSphere extent_;            // Skeleton Root over every schedule clip
    std::vector<Vec3> positions_;
    std::vector<double> headings_;
    std::vector<ClipChoice> choices_;
};

/// What a key-pose cache did in one frame (ActorFrameStatistics' key-pose counts, with the time).
struct TimelineFrame {
    std::uint32_t frame = 0;       ///< frame number, from 0
    double time = 0.0;             ///< seconds
    std::uint32_t phase = 0;       ///< schedule phase
    std::uint32_t available = 0;   ///< clips offered
    std::uint64_t band = 0;        ///< actors in the cache's band
    std::uint64_t served = 0;      ///< of those, drawn from the cache
    std::uint64_t misses = 0;      ///< of those, skinned: a key-pose they need was not held
    std::uint64_t updates = 0;     ///< key-poses newly stored in a row
    std::uint64_t wanted = 0;      ///< distinct key-poses the band needed
    std::uint64_t held = 0;        ///< key-poses held after the update
};

/// One phase of a timeline, averaged over its frames.
struct TimelinePhase {
    std::uint32_t phase = 0;         ///< schedule phase
    std::uint32_t available = 0;     ///< clips offered
    double start = 0.0;              ///< time of its first frame (s)
    double end = 0.0;                ///< time of its last frame (s)
    std::size_t frames = 0;          ///< frames in it
    double band = 0.0;               ///< mean actors in the band
    double servedShare = 0.0;        ///< mean share of the band served (0-1; frames with an empty band count as 1)
    double minServedShare = 1.0;     ///< the smallest share of a frame
    double servedSd = 0.0;           ///< standard deviation of the actors served a frame (how steady the count is)
    double misses = 0.0;             ///< mean misses a frame
    double updates = 0.0;            ///< mean updates a frame
    std::uint64_t firstUpdates = 0;  ///< updates in its first frame (the actors' new choices arrive)
    double laterUpdates = 0.0;       ///< mean updates a frame after the first (the steady rate; 0 for a one-frame phase)
    double laterUpdatesSd = 0.0;     ///< their standard deviation (how constant the rate is)
    double wanted = 0.0;             ///< mean distinct key-poses needed
};

/// The frames grouped by phase (consecutive frames of one phase form one entry, in order).
std::vector<TimelinePhase> summarizeTimeline(std::span<const TimelineFrame> frames);

/// Writes `frames` as CSV lines prefixed by `mode` (no header: writeTimelineCsvHeader writes it).
void writeTimelineCsv(std::ostream& out, const std::string& mode, std::span<const TimelineFrame> frames);
/// The header line of writeTimelineCsv's lines.
void writeTimelineCsvHeader(std::ostream& out);

}  // namespace throng::bench
