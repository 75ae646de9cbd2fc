#include "throng/sim/Locomotion.h"

#include <DetourCrowd.h>
#include <DetourNavMeshQuery.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/ClipBlend.h"
#include "throng/sim/CounterRng.h"

namespace throng::sim {
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
    if (counters_) {
        counters_->constructed("locomotion");
        if (settings_.avoidance) counters_->constructed("avoidance");
    }
}

Locomotion::~Locomotion() { dtFreeCrowd(crowd_); }

std::uint32_t Locomotion::addActor(const Actor& a) {
    const std::string where = "Locomotion::addActor";
    if (crowd_) throw std::invalid_argument(where + ": actors must be added before the first frame");
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
    State s;
    s.position = *onMesh;
    s.heading = static_cast<float>(CounterRng(settings_.seed, a.stream).uniform(~0ull, -kPi, kPi));
    // Extent of the Skeleton Root: both clips' root channels.
    BoundingSphere extent(Vec3(0.0), 0.0);
    for (int clip : {a.walkClip, a.runClip}) {
        if (clip < 0) continue;
        const AnimationClip& c = *clips[std::size_t(clip)];
        for (int k = 0; k <= 240; ++k) extent.expandBy(Vec3(c.sampleRoot(c.duration() * k / 240.0, false).translation));
    }
    extent.inflate(0.01);
    s.extent = extent;
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
        s.blendMargin = std::max(0.0, worst - a.tmpl->skeletonRootRadius()) + 0.02;
    }
    actors_.push_back(a);
    state_.push_back(s);
    return static_cast<std::uint32_t>(actors_.size() - 1);
}

void Locomotion::newDestination(std::uint32_t slot) {
    State& s = state_[slot];
    const Actor& a = actors_[slot];
    if (a.goal && s.trips > 0) return;  // there, or on its way: a fixed goal is asked for once
    const CounterRng rng(settings_.seed, a.stream);
    s.target = a.goal ? *a.goal : nav_->randomPoint(rng, s.trips);
    ++s.trips;
    dtQueryFilter filter;
    const glm::vec3 extents(2.0f, 4.0f, 2.0f);
    dtPolyRef ref = 0;
    glm::vec3 snapped;
    nav_->query()->findNearestPoly(&s.target.x, &extents.x, &filter, &ref, &snapped.x);
    if (ref) crowd_->requestMoveTarget(s.agent, ref, &snapped.x);
}

void Locomotion::start() {
    crowd_ = dtAllocCrowd();
    if (!crowd_ || !crowd_->init(static_cast<int>(std::max<std::size_t>(actors_.size(), 1)), settings_.radius, nav_->detourMesh()))
        throw std::runtime_error("Locomotion: DetourCrowd could not be initialised for " + std::to_string(actors_.size()) + " agents");
    for (std::uint32_t slot = 0; slot < actors_.size(); ++slot) {
        const Actor& a = actors_[slot];
        dtCrowdAgentParams p{};
        p.radius = settings_.radius;
        p.height = settings_.height;
        p.maxAcceleration = settings_.maxAcceleration;
        p.maxSpeed = static_cast<float>(a.speed);
        p.collisionQueryRange = settings_.radius * 12.0f;
        p.pathOptimizationRange = settings_.radius * 30.0f;
        p.updateFlags = DT_CROWD_ANTICIPATE_TURNS | DT_CROWD_OPTIMIZE_VIS | DT_CROWD_OPTIMIZE_TOPO;
        if (settings_.avoidance) p.updateFlags |= DT_CROWD_OBSTACLE_AVOIDANCE | DT_CROWD_SEPARATION;
        p.obstacleAvoidanceType = 3;
        p.separationWeight = 2.0f;
        state_[slot].agent = crowd_->addAgent(&state_[slot].position.x, &p);
        if (state_[slot].agent < 0) throw std::runtime_error("Locomotion: DetourCrowd refused agent " + std::to_string(slot));
        newDestination(slot);
    }
}

void Locomotion::advance(const FrameContext& context) {
    if (!crowd_) start();
    const float dt = static_cast<float>(context.deltaTime);
    if (dt <= 0.0f) return;
    for (std::uint32_t slot = 0; slot < actors_.size(); ++slot) {
        const State& s = state_[slot];
        const glm::vec3 d = s.target - s.position;
        if (d.x * d.x + d.z * d.z < 1.0f) newDestination(slot);
    }
    crowd_->update(dt, nullptr);
    if (counters_) {
        counters_->ticked("locomotion", actors_.size());
        if (settings_.avoidance) counters_->ticked("avoidance", actors_.size());
    }
    // Per agent, in parallel: each touches its own state only.
    forEachChunk(actors_.size(), 256, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t slot = begin; slot < end; ++slot) {
            State& s = state_[slot];
            const Actor& a = actors_[slot];
            const dtCrowdAgent* agent = crowd_->getAgent(s.agent);
            s.position = glm::vec3(agent->npos[0], agent->npos[1], agent->npos[2]);
            const glm::vec3 v(agent->vel[0], 0.0f, agent->vel[2]);
            s.speed = glm::length(v);
            if (s.speed > 0.05f) {  // face the way it goes, turning at a bounded rate
                const float want = std::atan2(v.x, v.z);
                const float turn = std::clamp(wrapAngle(want - s.heading), -settings_.turnRate * dt, settings_.turnRate * dt);
                s.heading = wrapAngle(s.heading + turn);
            }
            // Speed matching: the walk cycle advances as far as the actor walked, in double with the
            // exact step (a float step runs the cycle 5e-8 fast: 2e-4 cycles in a million steps).
            const double walkDuration = a.tmpl->clips()[std::size_t(a.walkClip)]->duration();
            const double clipSpeed = a.runClip < 0 ? a.walkClipSpeed
                                                   : a.walkClipSpeed + (a.runClipSpeed - a.walkClipSpeed) * s.runWeight;
            if (walkDuration > 0.0) s.phase = std::fmod(s.phase + context.deltaTime * s.speed / (clipSpeed * walkDuration), 1.0);
            if (a.runClip >= 0) {
                const float u = std::clamp(float((s.speed - a.walkClipSpeed) / (a.runClipSpeed - a.walkClipSpeed)), 0.0f, 1.0f);
                s.runWeight = u * u * (3.0f - 2.0f * u);
            }
        }
    });
}

double Locomotion::clipTime(std::uint32_t slot, double) const {
    // The walk cycle's phase follows the distance walked, not the clock.
    const Actor& a = actors_[slot];
    return state_[slot].phase * a.tmpl->clips()[std::size_t(a.walkClip)]->duration();
}

Mat4 Locomotion::referencePoint(std::uint32_t slot, const FrameContext&, OpTally* ops) {
    const State& s = state_[slot];
    const double c = std::cos(double(s.heading)), sn = std::sin(double(s.heading));
    THRONG_TALLY(ops, 0, 0, 0, 2);
    Mat4 m(1.0);
    m[0] = Vec4(c, 0.0, -sn, 0.0);
    m[2] = Vec4(sn, 0.0, c, 0.0);
    m[3] = Vec4(Vec3(s.position), 1.0);
    return m;
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
    const State& s = state_[slot];
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
