#include "throng/sim/GazeLayer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/CounterRng.h"

namespace throng::sim {
namespace {

bool nameHas(const std::string& name, const char* word) {
    std::string lower(name);
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    return lower.find(word) != std::string::npos;
}

// Model transform (Skeleton Root frame) of `node` from the current DOF values, along its chain.
Affine modelOf(const ActorTemplate& t, int node, std::span<const float> dofs, OpTally* ops) {
    std::vector<int> chain;
    for (int n = node; n >= 0; n = t.nodes()[std::size_t(n)].parent) chain.push_back(n);
    Affine m;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        const Affine local = nodeLocalTransform(t.nodes()[std::size_t(*it)], dofs.data() + t.dofOffset(std::size_t(*it)), ops);
        m = it == chain.rbegin() ? local : compose(m, local, ops);
    }
    return m;
}

glm::dquat rotationOf(const Affine& a) {
    glm::dmat3 r(a.linear);
    for (int c = 0; c < 3; ++c) r[c] = glm::normalize(r[c]);
    return glm::normalize(glm::quat_cast(r));
}

}  // namespace

GazeLayer::GazeLayer(std::shared_ptr<Behaviour> base, Settings settings, EffectCounters* counters)
    : BehaviourLayer(std::move(base), "GazeLayer"), settings_(std::move(settings)), counters_(counters) {
    const auto& g = settings_.levels;
    for (std::size_t i = 0; i < g.size(); ++i)
        if (std::isnan(g[i]) || g[i] <= 0.0 || (i > 0 && g[i] <= g[i - 1]))
            throw std::invalid_argument("GazeLayer: gaze level ends must be positive and increasing");
    if (!(settings_.range > 0.0)) throw std::invalid_argument("GazeLayer: range must be positive");
    // The base's bands merged with the gaze's; the gaze's level of each merged band.
    for (const double mid : mergeBands({g})) {
        int gl = 0;
        while (gl < int(g.size()) && !(mid < g[std::size_t(gl)])) ++gl;
        gazeLevel_.push_back(gl);
    }
    if (counters_) counters_->constructed("gaze");
}

GazeLayer::Joints GazeLayer::jointsOf(const ActorTemplate& tmpl) {
    if (const auto it = joints_.find(&tmpl); it != joints_.end()) return it->second;
    Joints j;
    for (std::size_t i = 0; i < tmpl.nodeCount() && j.neck < 0; ++i)
        if (nameHas(tmpl.nodes()[i].name, "neck")) j.neck = int(i);
    if (j.neck >= 0)
        for (std::size_t i = std::size_t(j.neck) + 1; i < tmpl.subtreeEnd(std::size_t(j.neck)); ++i)
            if (nameHas(tmpl.nodes()[i].name, "head")) {
                j.head = int(i);
                break;
            }
    joints_[&tmpl] = j;
    return j;
}

std::uint32_t GazeLayer::wrap(std::uint32_t baseSlot, const std::shared_ptr<const ActorTemplate>& tmpl, std::uint64_t stream) {
    if (!tmpl) throw std::invalid_argument("GazeLayer::wrap: argument 'tmpl' is null");
    if (state_.size() <= baseSlot) state_.resize(std::size_t(baseSlot) + 1);
    State& s = state_[baseSlot];
    s.tmpl = tmpl.get();
    s.joints = jointsOf(*tmpl);
    s.stream = stream;
    if (s.joints.neck >= 0) {
        // Turning the neck by at most maxYaw + maxPitch moves the parts it carries by at most their
        // distance from it times that angle: the Sklsroot Bsphere grows by that much.
        std::vector<Affine> model(tmpl->nodeCount());
        std::vector<BoundingSphere> geometry(tmpl->nodeCount()), subtree(tmpl->nodeCount());
        computeModelTransforms(*tmpl, tmpl->restDofs(), {}, model);
        computeInternalSpheres(*tmpl, model, {}, geometry, subtree);
        const Vec3 neck(model[std::size_t(s.joints.neck)].translation);
        double far = 0.0;
        for (std::size_t i = std::size_t(s.joints.neck); i < tmpl->subtreeEnd(std::size_t(s.joints.neck)); ++i)
            if (geometry[i].valid()) far = std::max(far, glm::length(geometry[i].center() - neck) + geometry[i].radius());
        s.margin = far * (settings_.maxYaw + settings_.maxPitch);
    }
    return baseSlot;
}

void GazeLayer::advance(const FrameContext& context) {
    base_->advance(context);  // the layer owns its base: the crowd only knows the layer
    const std::size_t n = state_.size();
    if (n == 0) return;
    // Positions of the actors known in this process (every one, unless another process steps
    // some of them and sent only those near the view).
    present_.resize(n);
    forEachChunk(n, 512, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            present_[i] = state_[i].tmpl && base_->known(std::uint32_t(i));
            if (present_[i]) state_[i].position = Vec3(base_->referencePoint(std::uint32_t(i), context, nullptr)[3]);
        }
    });
    // Neighbours come from a grid of cells one range wide.
    glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (std::size_t i = 0; i < n; ++i)
        if (present_[i]) {
            lo = glm::min(lo, glm::dvec2(state_[i].position.x, state_[i].position.z));
            hi = glm::max(hi, glm::dvec2(state_[i].position.x, state_[i].position.z));
        }
    const double cell = settings_.range;
    const int nx = std::clamp(int((hi.x - lo.x) / cell) + 1, 1, 4096), nz = std::clamp(int((hi.y - lo.y) / cell) + 1, 1, 4096);
    auto cellOf = [&](const glm::dvec3& p) {
        return std::clamp(int((p.z - lo.y) / cell), 0, nz - 1) * nx + std::clamp(int((p.x - lo.x) / cell), 0, nx - 1);
    };
    cellStart_.assign(std::size_t(nx) * std::size_t(nz) + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
        if (present_[i]) ++cellStart_[std::size_t(cellOf(state_[i].position)) + 1];
    for (std::size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
    cellFill_.assign(cellStart_.begin(), cellStart_.end() - 1);
    cellActors_.resize(cellStart_.back());
    cellPositions_.resize(cellStart_.back());
    for (std::size_t j = 0; j < n; ++j)
        if (present_[j]) {
            const std::uint32_t k = cellFill_[std::size_t(cellOf(state_[j].position))]++;
            cellActors_[k] = std::uint32_t(j);
            cellPositions_[k] = glm::dvec2(state_[j].position.x, state_[j].position.z);
        }
    // Each actor looks, for one of its periods (a few seconds, its own length and phase), at whoever
    // within range draws its lowest number for that period: anyone near is equally likely, the
    // choice holds while the same people stay near, and it depends on nothing but who is near now.
    // Per actor, in parallel: each reads positions and writes only its own choice.
    const double range2 = settings_.range * settings_.range;
    forEachChunk(n, 256, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            if (!present_[i]) continue;
            State& s = state_[i];
            const CounterRng rng(settings_.seed, s.stream);
            const double period = rng.uniform(0, 2.5, 5.0);
            const auto bucket = std::uint64_t(std::floor((context.time + rng.uniform(1, 0.0, period)) / period));
            int chosen = -1;
            std::uint64_t lowest = 0;
            const int c = cellOf(s.position), cx = c % nx, cz = c / nx;
            for (int z = std::max(0, cz - 1); z <= std::min(nz - 1, cz + 1); ++z)
                for (int x = std::max(0, cx - 1); x <= std::min(nx - 1, cx + 1); ++x)
                    for (std::uint32_t k = cellStart_[std::size_t(z * nx + x)]; k < cellStart_[std::size_t(z * nx + x) + 1]; ++k) {
                        // Positions read beside the cell's actors, not from each actor's state: the
                        // candidates' states lie all over memory, and most are out of range.
                        const glm::dvec2 d = cellPositions_[k] - glm::dvec2(s.position.x, s.position.z);
                        if (d.x * d.x + d.y * d.y > range2) continue;
                        const std::uint32_t j = cellActors_[k];
                        if (j == i) continue;
                        const std::uint64_t draw = rng.bits((bucket << 32) ^ (std::uint64_t(j) + 2));  // counters 0 and 1 set the period
                        if (chosen < 0 || draw < lowest || (draw == lowest && int(j) < chosen)) chosen = int(j), lowest = draw;
                    }
            s.target = chosen;
            s.lookAt = chosen >= 0 ? state_[std::size_t(chosen)].position + glm::dvec3(0, settings_.eyeHeight, 0)
                                   : s.position + glm::dvec3(0, settings_.eyeHeight, 0);
        }
    });
    if (counters_) counters_->ticked("gaze", n);
}

void GazeLayer::turn(const ActorTemplate& tmpl, int node, const glm::dquat& q, std::span<float> dofs,
                     std::span<const std::uint8_t> active, OpTally* ops) const {
    if (node < 0 || (!active.empty() && !active[std::size_t(node)])) return;
    const SkeletonNode& n = tmpl.nodes()[std::size_t(node)];
    const glm::dquat parent = n.parent >= 0 ? rotationOf(modelOf(tmpl, n.parent, dofs, ops)) : glm::dquat(1, 0, 0, 0);
    for (std::size_t d = 0; d < n.dofs.size(); ++d) {
        float* v = dofs.data() + tmpl.dofValueOffset(std::size_t(node), d);
        if (n.dofs[d].kind == DofKind::Orientation) {
            // Rotate the node's frame by q about its own origin, in the Skeleton Root frame.
            const glm::dquat rest(n.restRotation), current(v[3], v[0], v[1], v[2]);
            const glm::dquat turned = glm::normalize(glm::inverse(rest) * glm::inverse(parent) * q * parent * rest * current);
            v[0] = float(turned.x), v[1] = float(turned.y), v[2] = float(turned.z), v[3] = float(turned.w);
            THRONG_TALLY(ops, 80, 60, 0, 1);
            return;
        }
    }
    // Axis DOFs (procedural templates): yaw onto the vertical axis, pitch onto the sideways one.
    const glm::dvec3 euler = glm::eulerAngles(q);
    for (std::size_t d = 0; d < n.dofs.size(); ++d) {
        const Dof& dof = n.dofs[d];
        if (dof.kind != DofKind::RotateAxis) continue;
        float* v = dofs.data() + tmpl.dofValueOffset(std::size_t(node), d);
        if (std::abs(dof.axis.y) > 0.9f) *v = std::clamp(*v + float(euler.y) * (dof.axis.y > 0 ? 1.0f : -1.0f), dof.min, dof.max);
        if (std::abs(dof.axis.x) > 0.9f) *v = std::clamp(*v + float(euler.x) * (dof.axis.x > 0 ? 1.0f : -1.0f), dof.min, dof.max);
    }
    THRONG_TALLY(ops, 10, 10, 0, 2);
}

void GazeLayer::pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
                     std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) {
    if (slot < state_.size() && state_[slot].tmpl) {  // last frame's turn does not carry over
        restNode(tmpl, state_[slot].joints.neck, dofs);
        restNode(tmpl, state_[slot].joints.head, dofs);
    }
    base_->pose(slot, time, baseLevel(level), tmpl, active, dofs, ops);
    const int gazeLevel = gazeLevel_[std::size_t(level)];
    if (slot >= state_.size() || !state_[slot].tmpl) return;
    const State& s = state_[slot];
    if (gazeLevel >= int(settings_.levels.size()) || s.joints.neck < 0) return;
    if (!active.empty() && !active[std::size_t(s.joints.neck)]) return;  // a deactivated neck does not turn
    // Where to look, in the Skeleton Root frame.
    const FrameContext none{time, 0.0, 0, nullptr};
    const Mat4 ref = base_->referencePoint(slot, none, ops);
    const RootPose root = base_->skeletonRoot(slot, time, baseLevel(level), ops);
    const Mat4 skeletonRoot = ref * rootPoseMatrix(root);
    const glm::dvec3 target = glm::dvec3(glm::inverse(skeletonRoot) * glm::dvec4(s.lookAt, 1.0));
    const glm::dvec3 neck(modelOf(tmpl, s.joints.neck, dofs, ops).translation);
    const glm::dvec3 d = target - neck;
    const double yaw = std::clamp(std::atan2(d.x, d.z), -settings_.maxYaw, settings_.maxYaw);
    const double pitch = std::clamp(std::atan2(d.y, std::sqrt(d.x * d.x + d.z * d.z)), -settings_.maxPitch, settings_.maxPitch);
    THRONG_TALLY(ops, 12, 10, 0, 3);
    const glm::dquat look = glm::angleAxis(yaw, glm::dvec3(0, 1, 0)) * glm::angleAxis(-pitch, glm::dvec3(1, 0, 0));
    if (gazeLevel == 0 && s.joints.head >= 0 && (active.empty() || active[std::size_t(s.joints.head)])) {
        // Near: the neck turns most of the way, the head the rest.
        const glm::dquat neckTurn = glm::slerp(glm::dquat(1, 0, 0, 0), look, 0.6);
        turn(tmpl, s.joints.neck, neckTurn, dofs, active, ops);
        turn(tmpl, s.joints.head, look * glm::inverse(neckTurn), dofs, active, ops);
    } else {
        turn(tmpl, s.joints.neck, look, dofs, active, ops);  // farther: the neck alone
    }
}

}  // namespace throng::sim
