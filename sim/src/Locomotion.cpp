// The walker behaviour of Locomotion, and each step's order: the region stepper moves the walkers,
// the rank exchange carries records between ranks (sim/src/locomotion/), this file turns each
// walker's motion into a gait and poses it.

#include "throng/sim/Locomotion.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/detail/SinCos.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/ClipBlend.h"
#include "throng/sim/CounterRng.h"
#include "throng/sim/PeakMemory.h"
#include "throng/sim/Ranks.h"
#include "locomotion/RankExchange.h"
#include "locomotion/RegionStepper.h"
#include "locomotion/WalkerState.h"

namespace throng::sim {

using locomotion::WalkerState;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
float wrapAngle(float a) {
    while (a > kPi) a -= 2 * kPi;
    while (a < -kPi) a += 2 * kPi;
    return a;
}

// The farthest any part of `tmpl` gets from its Skeleton Root in pose `dofs`.
double farthestPart(const ActorTemplate& tmpl, std::span<const float> dofs) {
    std::vector<Affine> model(tmpl.nodeCount());
    std::vector<BoundingSphere> geometry(tmpl.nodeCount()), subtree(tmpl.nodeCount());
    computeModelTransforms(tmpl, dofs, {}, model);
    computeInternalSpheres(tmpl, model, {}, geometry, subtree);
    double far = 0.0;
    for (const BoundingSphere& g : geometry)
        if (g.valid()) far = std::max(far, glm::length(g.center()) + g.radius());
    return far;
}

}  // namespace

Locomotion::Locomotion(std::shared_ptr<const NavMesh> navMesh, Settings settings, std::vector<double> levelEnds,
                       EffectCounters* counters)
    : nav_(std::move(navMesh)), settings_(settings), levelEnds_(std::move(levelEnds)), counters_(counters) {
    if (!nav_) throw std::invalid_argument("Locomotion: argument 'navMesh' is null");
    for (std::size_t i = 0; i < levelEnds_.size(); ++i)
        if (std::isnan(levelEnds_[i]) || levelEnds_[i] <= 0.0 || (i > 0 && levelEnds_[i] <= levelEnds_[i - 1]))
            throw std::invalid_argument("Locomotion: level ends must be positive and increasing");
    if (settings_.avoidanceQuality < 0 || settings_.avoidanceQuality > 3)
        throw std::invalid_argument("Locomotion: avoidance quality must be 0 to 3, not " + std::to_string(settings_.avoidanceQuality));
    if (!(settings_.farDistance >= 0.0) || !std::isfinite(settings_.farDistance) || settings_.farEvery < 1 || settings_.farEvery > 1000)
        throw std::invalid_argument("Locomotion: far regions need a distance of 0 m or more and a rate of 1 to 1000 steps, not " +
                                    std::to_string(settings_.farDistance) + " m and " + std::to_string(settings_.farEvery));
    if (!(settings_.neighbourRange >= 1.0f) || !std::isfinite(settings_.neighbourRange))
        throw std::invalid_argument("Locomotion: the neighbour range must be at least 1 agent radius, not " +
                                    std::to_string(settings_.neighbourRange));
    if (counters_) {
        counters_->constructed("locomotion");
        if (settings_.avoidance) counters_->constructed("avoidance");
    }
}

Locomotion::~Locomotion() = default;

std::uint32_t Locomotion::addActor(const Actor& a) {
    const std::string where = "Locomotion::addActor";
    if (started_) throw std::invalid_argument(where + ": actors must be added before the first frame");
    if (!a.tmpl) throw std::invalid_argument(where + ": argument 'actor.tmpl' is null");
    const auto clips = a.tmpl->clips();
    if (a.walkClip < 0 || std::size_t(a.walkClip) >= clips.size())
        throw std::invalid_argument(where + ": template '" + a.tmpl->name() + "' has no walk clip " + std::to_string(a.walkClip));
    if (a.runClip >= 0 && std::size_t(a.runClip) >= clips.size())
        throw std::invalid_argument(where + ": template '" + a.tmpl->name() + "' has no run clip " + std::to_string(a.runClip));
    if (!(a.walkClipSpeed > 0) || !(a.runClipSpeed > a.walkClipSpeed || a.runClip < 0) || !(a.speed > 0) ||
        !std::isfinite(a.speed) || !std::isfinite(a.walkClipSpeed) || !std::isfinite(a.runClipSpeed))
        throw std::invalid_argument(where + ": speeds must be positive, finite and the run clip's above the walk clip's");
    const auto onMesh = nav_->nearestPoint(a.start, glm::vec3(5.0f, 10.0f, 5.0f));
    if (!onMesh)
        throw std::invalid_argument(where + ": start (" + std::to_string(a.start.x) + ", " + std::to_string(a.start.y) + ", " +
                                    std::to_string(a.start.z) + ") is not near the navigation mesh");
    if (a.goal && !nav_->nearestPoint(*a.goal, glm::vec3(5.0f, 10.0f, 5.0f)))
        throw std::invalid_argument(where + ": goal (" + std::to_string(a.goal->x) + ", " + std::to_string(a.goal->y) + ", " +
                                    std::to_string(a.goal->z) + ") is not near the navigation mesh");
    WalkerState s;
    s.position = *onMesh;
    s.heading = static_cast<float>(CounterRng(settings_.seed, a.stream).uniform(~0ull, -kPi, kPi));
    // The Skeleton Root's extent and the blends' margin depend on the template and clips only:
    // measured once for each (a crowd of a million shares a handful).
    auto known = std::find_if(clipBounds_.begin(), clipBounds_.end(), [&](const ClipBounds& c) {
        return c.tmpl == a.tmpl.get() && c.walkClip == a.walkClip && c.runClip == a.runClip;
    });
    if (known == clipBounds_.end()) {
        ClipBounds bounds{a.tmpl.get(), a.walkClip, a.runClip, {}, 0.0};
        BoundingSphere extent(Vec3(0.0), 0.0);
        for (int clip : {a.walkClip, a.runClip}) {
            if (clip < 0) continue;
            const AnimationClip& c = *clips[std::size_t(clip)];
            for (int k = 0; k <= 240; ++k) extent.expandBy(Vec3(c.sampleRoot(c.duration() * k / 240.0, false).translation));
        }
        extent.inflate(0.01);
        bounds.extent = extent;
        // Blends of walk and run can reach beyond either clip: measure how far, over a few phases.
        if (a.runClip >= 0) {
            const AnimationClip &walk = *clips[std::size_t(a.walkClip)], &run = *clips[std::size_t(a.runClip)];
            std::vector<float> pw(a.tmpl->restDofs().begin(), a.tmpl->restDofs().end()), pr = pw, blend = pw;
            double worst = 0.0;
            for (int k = 0; k < 16; ++k) {
                walk.sample(*a.tmpl, walk.duration() * k / 16.0, true, {}, pw);
                run.sample(*a.tmpl, run.duration() * k / 16.0, true, {}, pr);
                for (float w : {0.25f, 0.5f, 0.75f}) {
                    blendPoses(*a.tmpl, pw, pr, w, {}, blend);
                    worst = std::max(worst, farthestPart(*a.tmpl, blend));
                }
            }
            bounds.blendMargin = std::max(0.0, worst - a.tmpl->skeletonRootRadius()) + 0.02;
        }
        clipBounds_.push_back(bounds);
        known = clipBounds_.end() - 1;
    }
    s.extent = known->extent;
    s.blendMargin = known->blendMargin;
    actors_.push_back(a);
    state_.push_back(s);
    regionOf_.push_back(0);
    return static_cast<std::uint32_t>(actors_.size() - 1);
}

void Locomotion::start() {
    started_ = true;
    regions_ = std::make_unique<locomotion::RegionStepper>(*nav_, settings_, actors_, state_, regionOf_);
    regions_->place();
    firstRegion_ = 0, endRegion_ = regions_->count();
    if (ranks_) {
        exchange_ = std::make_unique<locomotion::RankExchange>(*ranks_, state_, regionOf_);
        exchange_->setPosing(posedWhereStepped_);
        std::tie(firstRegion_, endRegion_) = exchange_->assign(*regions_);
    }
    regions_->start(firstRegion_, endRegion_);
}

void Locomotion::distribute(Ranks& ranks) {
    if (started_) throw std::logic_error("Locomotion::distribute: the crowd has already started");
    ranks_ = &ranks;
}

void Locomotion::setPosedWhereStepped(bool posed) {
    if (started_) throw std::logic_error("Locomotion::setPosedWhereStepped: the crowd has already started");
    if (!ranks_) throw std::logic_error("Locomotion::setPosedWhereStepped: the walkers are not distributed over ranks");
    posedWhereStepped_ = posed;
}

std::uint8_t Locomotion::carried(std::uint32_t slot) const { return state_[slot].carried; }
void Locomotion::setCarried(std::uint32_t slot, std::uint8_t value) { state_[slot].carried = value; }

void Locomotion::setGatherView(std::optional<Frustum> view, double margin, double shownMargin) {
    if (!std::isfinite(margin) || margin < 0.0)
        throw std::invalid_argument("Locomotion::setGatherView: argument 'margin' must be finite and >= 0, not " + std::to_string(margin));
    if (!std::isfinite(shownMargin) || shownMargin < 0.0 || shownMargin > margin)
        throw std::invalid_argument("Locomotion::setGatherView: argument 'shownMargin' must be finite, >= 0 and at most the margin (" +
                                    std::to_string(margin) + "), not " + std::to_string(shownMargin));
    gatherView_ = std::move(view);
    gatherMargin_ = margin;
    shownMargin_ = shownMargin;
}

void Locomotion::advance(const FrameContext& context) {
    if (!started_) start();
    const float dt = static_cast<float>(context.deltaTime);
    const Stopwatch watch;
    RankStepRecord mine;
    locomotion::RegionStepper& regions = *regions_;
    if (dt <= 0.0f) {
        // Nobody moves. Posing where stepped, every rank still learns which walkers it shows.
        if (posedWhereStepped_) listOwn(), gatherOwn(mine, watch);
        return;
    }
    // Which regions step now: every one, unless the scene lets far ones step less often.
    lastDeferred_ = mine.deferred = regions.chooseStepping(firstRegion_, endRegion_, context.deltaTime, viewpoint_);
    auto eachRegion = [&](auto&& body) {
        forEachChunk(endRegion_ - firstRegion_, 1, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t r = begin; r < end; ++r) body(firstRegion_ + std::uint32_t(r));
        });
    };
    // Ghosts: every region lists its agents near another region; each region takes in what the
    // others sent it, in order of the sending region and then of slot.
    eachRegion([&](std::uint32_t r) { regions.exportGhosts(r); });
    if (!ranks_) {
        lastGhosts_ = regions.deliverGhosts();
    } else {
        for (std::uint32_t r = firstRegion_; r < endRegion_; ++r)
            for (const locomotion::GhostRecord& g : regions.region(r).ghostsOut)
                ++mine.ghosts, mine.ghostsToRanks += exchange_->rankOf(g.region) != exchange_->rank();
        const Stopwatch wait;
        mine.borderBytes += exchange_->routeGhosts(regions);
        mine.waitMs += wait.elapsedMs();
        lastGhosts_ = mine.ghosts;
    }
    regions.prepareStep();
    eachRegion([&](std::uint32_t r) { regions.stepRegion(r, dt); });
    // Handover: agents now in another region leave their crowd and join the other's.
    eachRegion([&](std::uint32_t r) { regions.exportHandovers(r); });
    if (!ranks_) {
        lastHandovers_ = regions.deliverHandovers();
    } else {
        for (std::uint32_t r = firstRegion_; r < endRegion_; ++r)
            for (const locomotion::HandoverRecord& h : regions.region(r).leaving) {
                ++mine.handovers;
                if (exchange_->rankOf(h.to) != exchange_->rank())  // gone: this rank no longer steps it
                    ++mine.handedToRanks, regionOf_[h.slot] = h.to;
            }
        const Stopwatch wait;
        mine.borderBytes += exchange_->routeHandovers(regions);
        mine.waitMs += wait.elapsedMs();
        lastHandovers_ = mine.handovers;
    }
    eachRegion([&](std::uint32_t r) { regions.importHandovers(r); });
    if (counters_) {
        counters_->ticked("locomotion", actors_.size());
        if (settings_.avoidance) counters_->ticked("avoidance", actors_.size());
    }
    // Per agent, in parallel: each touches its own state only.
    if (!ranks_) {
        forEachChunk(actors_.size(), 256, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t slot = begin; slot < end; ++slot) walk(std::uint32_t(slot), context.deltaTime);
        });
        lastAdvanceMs_ = watch.elapsedMs();
        return;
    }
    listOwn();
    forEachChunk(ownSlots_.size(), 256, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) walk(ownSlots_[k], context.deltaTime);
    });
    gatherOwn(mine, watch);
}

void Locomotion::listOwn() {
    ownSlots_.clear();
    for (std::uint32_t r = firstRegion_; r < endRegion_; ++r)
        ownSlots_.insert(ownSlots_.end(), regions_->region(r).owned.begin(), regions_->region(r).owned.end());
}

void Locomotion::gatherOwn(RankStepRecord& mine, const Stopwatch& watch) {
    mine.agents = ownSlots_.size();
    mine.workMs = watch.elapsedMs() - mine.waitMs;
    mine.peakBytes = peakResidentBytes();
    lastAdvanceMs_ = watch.elapsedMs();
    const locomotion::RankExchange::Totals totals = exchange_->gather(mine, ownSlots_, gatherView_, gatherMargin_, shownMargin_);
    if (exchange_->rank() == 0) lastGhosts_ = totals.ghosts, lastHandovers_ = totals.handovers, lastDeferred_ = totals.deferred;
}

void Locomotion::walk(std::uint32_t slot, double dt) {
    WalkerState& s = state_[slot];
    const Actor& a = actors_[slot];
    const glm::vec3 v(s.velocity.x, 0.0f, s.velocity.z);
    s.speed = glm::length(v);
    if (s.speed > 0.05f) {  // face the way it goes, turning at a bounded rate
        const float want = std::atan2(v.x, v.z);
        const float most = settings_.turnRate * static_cast<float>(dt);
        s.heading = wrapAngle(s.heading + std::clamp(wrapAngle(want - s.heading), -most, most));
    }
    // Speed matching: the walk cycle advances as far as the actor walked, in double with the
    // exact step (a float step runs the cycle 5e-8 fast: 2e-4 cycles in a million steps).
    const double walkDuration = a.tmpl->clips()[std::size_t(a.walkClip)]->duration();
    const double clipSpeed = a.runClip < 0 ? a.walkClipSpeed : a.walkClipSpeed + (a.runClipSpeed - a.walkClipSpeed) * s.runWeight;
    if (walkDuration > 0.0) s.phase = std::fmod(s.phase + dt * s.speed / (clipSpeed * walkDuration), 1.0);
    if (a.runClip >= 0) {
        const float u = std::clamp(float((s.speed - a.walkClipSpeed) / (a.runClipSpeed - a.walkClipSpeed)), 0.0f, 1.0f);
        s.runWeight = u * u * (3.0f - 2.0f * u);
    }
}

glm::vec3 Locomotion::position(std::uint32_t slot) const { return state_[slot].position; }
double Locomotion::speed(std::uint32_t slot) const { return state_[slot].speed; }
glm::vec3 Locomotion::destination(std::uint32_t slot) const { return state_[slot].target; }
std::uint32_t Locomotion::region(std::uint32_t slot) const { return regionOf_[slot]; }
BoundingSphere Locomotion::skeletonRootExtent(std::uint32_t slot) const { return state_[slot].extent; }
double Locomotion::poseMargin(std::uint32_t slot) const { return state_[slot].blendMargin; }
std::size_t Locomotion::stepBytes() const {
    if (!regions_) return 0;
    return actors_.capacity() * sizeof(Actor) + state_.capacity() * sizeof(locomotion::WalkerState) +
           regionOf_.capacity() * sizeof(std::uint32_t) + clipBounds_.capacity() * sizeof(ClipBounds) + ownSlots_.capacity() * sizeof(std::uint32_t) +
           regions_->bytes();
}

std::size_t Locomotion::bytesPerSlot() const { return sizeof(Actor) + sizeof(WalkerState) + sizeof(std::uint32_t); }
bool Locomotion::presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const {
    if (!exchange_ || exchange_->everyoneShown()) return true;
    for (std::size_t k = 0; k < slots.size(); ++k) present[k] = exchange_->shown(slots[k]);
    return false;
}
bool Locomotion::steppingRegions(std::span<const std::uint32_t> slots, std::span<std::uint32_t> regions) const {
    for (std::size_t k = 0; k < slots.size(); ++k) regions[k] = regionOf_[slots[k]];
    return true;
}
bool Locomotion::known(std::uint32_t slot) const { return !exchange_ || exchange_->known(slot); }
std::optional<std::span<const std::uint32_t>> Locomotion::presentSlots() const {
    return exchange_ ? exchange_->shownSlots() : std::nullopt;
}
std::size_t Locomotion::shownCount() const { return exchange_ ? exchange_->shownCount(actors_.size()) : actors_.size(); }
std::size_t Locomotion::presentCount() const { return exchange_ ? exchange_->presentCount(actors_.size()) : actors_.size(); }
std::span<const Locomotion::RankStepRecord> Locomotion::rankSteps() const {
    return exchange_ ? exchange_->rankSteps() : std::span<const RankStepRecord>();
}

double Locomotion::clipTime(std::uint32_t slot, double) const {
    // The walk cycle's phase follows the distance walked, not the clock.
    const Actor& a = actors_[slot];
    return state_[slot].phase * a.tmpl->clips()[std::size_t(a.walkClip)]->duration();
}

namespace {
// A walker's Reference Point: at its position, facing its heading, given the heading's sine and cosine.
Mat4 walkerRefpoint(const Vec3& position, double sn, double c) {
    Mat4 m(1.0);
    m[0] = Vec4(c, 0.0, -sn, 0.0);
    m[2] = Vec4(sn, 0.0, c, 0.0);
    m[3] = Vec4(position, 1.0);
    return m;
}
}  // namespace

Mat4 Locomotion::referencePoint(std::uint32_t slot, const FrameContext&, OpTally* ops) {
    const WalkerState& s = state_[slot];
    double sn, c;
    detail::sinCos(double(s.heading), sn, c);
    THRONG_TALLY(ops, 0, 0, 0, 2);
    return walkerRefpoint(Vec3(s.position), sn, c);
}

void Locomotion::referencePoints(std::span<const std::uint32_t> slots, const FrameContext&, OpTally* ops, std::span<Mat4> out) {
    constexpr std::size_t kBlock = 16;
    double headings[kBlock], sines[kBlock], cosines[kBlock];
    for (std::size_t first = 0; first < slots.size(); first += kBlock) {
        const std::size_t n = std::min(kBlock, slots.size() - first);
        for (std::size_t k = 0; k < n; ++k) headings[k] = double(state_[slots[first + k]].heading);
        detail::sinCos(headings, sines, cosines, n);
        for (std::size_t k = 0; k < n; ++k) {
            THRONG_TALLY(ops, 0, 0, 0, 2);
            out[first + k] = walkerRefpoint(Vec3(state_[slots[first + k]].position), sines[k], cosines[k]);
        }
    }
}

RootPose Locomotion::skeletonRoot(std::uint32_t slot, double, int level, OpTally* ops) {
    if (level >= static_cast<int>(levelEnds_.size())) return RootPose{};
    const Actor& a = actors_[slot];
    const AnimationClip& walk = *a.tmpl->clips()[std::size_t(a.walkClip)];
    return walk.sampleRoot(state_[slot].phase * walk.duration(), true, ops, level >= 1);
}

void Locomotion::pose(std::uint32_t slot, double, int level, const ActorTemplate& tmpl,
                      std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) {
    const Actor& a = actors_[slot];
    const WalkerState& s = state_[slot];
    if (level >= static_cast<int>(levelEnds_.size())) {  // beyond the last band: rest pose
        writeRestPose(tmpl, active, dofs);
        return;
    }
    const AnimationClip& walk = *tmpl.clips()[std::size_t(a.walkClip)];
    walk.sample(tmpl, s.phase * walk.duration(), true, active, dofs, ops, level >= 1);
    if (a.runClip >= 0 && s.runWeight > 0.0f && level == 0) {  // blending is level-0 detail
        thread_local std::vector<float> run;
        run.assign(dofs.begin(), dofs.end());
        const AnimationClip& r = *tmpl.clips()[std::size_t(a.runClip)];
        r.sample(tmpl, s.phase * r.duration(), true, active, run, ops);
        blendPoses(tmpl, dofs, run, s.runWeight, active, dofs);
    }
}

}  // namespace throng::sim
