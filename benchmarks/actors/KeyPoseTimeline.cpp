#include "KeyPoseTimeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/AnimationClip.h"
#include "throng/actors/RefpointPath.h"
#include "throng/actors/SkeletonPose.h"

namespace throng::bench {

std::uint32_t ClipSchedule::phaseAt(double time) const {
    if (!(time > 0.0)) return 0;  // NaN included: the start
    // The tolerance puts frame n / fps that should land on a boundary (150 / 30 = 5) in the new
    // phase even when the division rounds it just below.
    const double k = std::floor(time / phaseSeconds + 1e-9);
    return k >= double(clips) ? clips : static_cast<std::uint32_t>(k);
}

std::size_t chooseClips(std::span<ClipChoice> choices, std::uint32_t available, std::span<const double> durations, double share,
                        UnitRandom& random) {
    constexpr const char* where = "chooseClips";
    if (available == 0 || available > durations.size())
        throw std::invalid_argument(std::string(where) + ": " + std::to_string(available) + " clips available out of " +
                                    std::to_string(durations.size()));
    for (double d : durations)
        if (!(d > 0.0) || !std::isfinite(d)) throw std::invalid_argument(std::string(where) + ": a clip's duration is not positive and finite");
    if (!(share >= 0.0 && share <= 1.0)) throw std::invalid_argument(std::string(where) + ": share must be in [0, 1]");
    std::size_t chosen = 0;
    for (ClipChoice& c : choices) {
        const double again = random.next(), which = random.next(), when = random.next();  // always three draws
        if (c.clip < available && !(again < share)) continue;
        c.clip = std::min(available - 1, static_cast<std::uint32_t>(which * available));
        c.offset = when * durations[c.clip];
        ++chosen;
    }
    return chosen;
}

ClipChoiceBehaviour::ClipChoiceBehaviour(std::shared_ptr<const ActorTemplate> tmpl, std::vector<int> clips)
    : tmpl_(std::move(tmpl)), clips_(std::move(clips)), levelEnds_{std::numeric_limits<double>::infinity()} {
    constexpr const char* where = "ClipChoiceBehaviour";
    if (!tmpl_) throw std::invalid_argument(std::string(where) + ": the template is null");
    if (clips_.empty()) throw std::invalid_argument(std::string(where) + ": no clip to choose from");
    const auto all = tmpl_->clips();
    for (int c : clips_) {
        if (c < 0 || static_cast<std::size_t>(c) >= all.size())
            throw std::invalid_argument(std::string(where) + ": template '" + tmpl_->name() + "' has no clip " + std::to_string(c));
        const AnimationClip& clip = *all[static_cast<std::size_t>(c)];
        if (!(clip.duration() > 0.0) || !std::isfinite(clip.duration()))
            throw std::invalid_argument(std::string(where) + ": clip '" + clip.name() + "' has no positive duration to loop");
        durations_.push_back(clip.duration());
        // The Skeleton Root's places, sampled densely (cubic splines can overshoot their keys) and
        // at every key, as KeyframeBehaviour does for one clip; here for all, so a later choice
        // stays inside the sphere Crowd::add read once.
        const auto steps = static_cast<std::size_t>(std::ceil(clip.duration() * 240.0));
        for (std::size_t k = 0; k <= steps; ++k)
            extent_.expandBy(Vec3(clip.sampleRoot(clip.duration() * double(k) / double(steps), false).translation));
        for (const ClipChannel& ch : clip.channels())
            if (ch.target == ClipChannel::Target::RootTranslation)
                for (float t : ch.times) extent_.expandBy(Vec3(clip.sampleRoot(t, false).translation));
    }
    extent_.inflate(0.01);
}

void ClipChoiceBehaviour::check(const ClipChoice& choice, const char* where) const {
    if (choice.clip >= clips_.size())
        throw std::invalid_argument(std::string(where) + ": clip " + std::to_string(choice.clip) + " is not one of the " +
                                    std::to_string(clips_.size()) + " to choose from");
    if (!std::isfinite(choice.offset)) throw std::invalid_argument(std::string(where) + ": the offset is not finite");
}

std::uint32_t ClipChoiceBehaviour::addActor(const Vec3& position, double heading, const ClipChoice& choice) {
    constexpr const char* where = "ClipChoiceBehaviour::addActor";
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z) || !std::isfinite(heading))
        throw std::invalid_argument(std::string(where) + ": position or heading not finite");
    check(choice, where);
    positions_.push_back(position);
    headings_.push_back(heading);
    choices_.push_back(choice);
    return static_cast<std::uint32_t>(choices_.size() - 1);
}

void ClipChoiceBehaviour::setChoice(std::uint32_t slot, const ClipChoice& choice) {
    constexpr const char* where = "ClipChoiceBehaviour::setChoice";
    if (slot >= choices_.size()) throw std::invalid_argument(std::string(where) + ": no slot " + std::to_string(slot));
    check(choice, where);
    choices_[slot] = choice;
}

Mat4 ClipChoiceBehaviour::referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) {
    return RefpointPath{positions_[slot], headings_[slot], 0.0, 0.0}.at(context.time, ops);
}

RootPose ClipChoiceBehaviour::skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) {
    (void)level;  // one level: full detail
    const AnimationClip& clip = *tmpl_->clips()[static_cast<std::size_t>(mainClip(slot))];
    return clip.sampleRoot(clipTime(slot, time), true, ops);
}

void ClipChoiceBehaviour::pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
                               std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) {
    (void)level;
    tmpl.clips()[static_cast<std::size_t>(mainClip(slot))]->sample(tmpl, clipTime(slot, time), true, active, dofs, ops);
}

BoundingSphere ClipChoiceBehaviour::skeletonRootExtent(std::uint32_t slot) const {
    (void)slot;
    return extent_;
}

std::vector<TimelinePhase> summarizeTimeline(std::span<const TimelineFrame> frames) {
    std::vector<TimelinePhase> out;
    std::size_t first = 0;
    while (first < frames.size()) {
        std::size_t last = first;
        while (last + 1 < frames.size() && frames[last + 1].phase == frames[first].phase) ++last;
        TimelinePhase p;
        p.phase = frames[first].phase;
        p.available = frames[first].available;
        p.start = frames[first].time;
        p.end = frames[last].time;
        p.frames = last - first + 1;
        p.firstUpdates = frames[first].updates;
        double laterSum = 0.0, laterSquares = 0.0, served = 0.0, servedSquares = 0.0;
        for (std::size_t i = first; i <= last; ++i) {
            const TimelineFrame& f = frames[i];
            const double share = f.band > 0 ? double(f.served) / double(f.band) : 1.0;
            p.band += double(f.band);
            p.servedShare += share;
            p.minServedShare = std::min(p.minServedShare, share);
            p.misses += double(f.misses);
            p.updates += double(f.updates);
            p.wanted += double(f.wanted);
            served += double(f.served), servedSquares += double(f.served) * double(f.served);
            if (i > first) laterSum += double(f.updates), laterSquares += double(f.updates) * double(f.updates);
        }
        const double n = double(p.frames);
        for (double* v : {&p.band, &p.servedShare, &p.misses, &p.updates, &p.wanted}) *v /= n;
        p.servedSd = std::sqrt(std::max(0.0, servedSquares / n - (served / n) * (served / n)));
        if (p.frames > 1) {
            const double m = laterSum / (n - 1.0);
            p.laterUpdates = m;
            p.laterUpdatesSd = std::sqrt(std::max(0.0, laterSquares / (n - 1.0) - m * m));
        }
        out.push_back(p);
        first = last + 1;
    }
    return out;
}

void writeTimelineCsvHeader(std::ostream& out) {
    out << "mode,frame,time,phase,clips_available,band,served,misses,updates,wanted,held\n";
}

void writeTimelineCsv(std::ostream& out, const std::string& mode, std::span<const TimelineFrame> frames) {
    for (const TimelineFrame& f : frames) {
        char time[32];
        std::snprintf(time, sizeof time, "%.4f", f.time);  // whatever the stream's precision
        out << mode << ',' << f.frame << ',' << time << ',' << f.phase << ',' << f.available << ',' << f.band << ',' << f.served
            << ',' << f.misses << ',' << f.updates << ',' << f.wanted << ',' << f.held << '\n';
    }
}

}  // namespace throng::bench
