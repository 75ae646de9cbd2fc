#include "throng/actors/KeyframeBehaviour.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/RefpointPath.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/Validation.h"

namespace throng {
namespace {

void checkLevelEnds(const std::vector<double>& ends, const char* who) {
    for (std::size_t i = 0; i < ends.size(); ++i)
        if (std::isnan(ends[i]) || ends[i] <= 0.0 || (i > 0 && ends[i] <= ends[i - 1]))
            throw std::invalid_argument(std::string(who) + ": level ends must be positive and increasing");
}

}  // namespace

KeyframeBehaviour::KeyframeBehaviour(std::vector<double> levelEnds) : levelEnds_(std::move(levelEnds)) {
    checkLevelEnds(levelEnds_, "KeyframeBehaviour");
}

std::uint32_t KeyframeBehaviour::addActor(const Actor& a) {
    constexpr const char* where = "KeyframeBehaviour::addActor";
    if (!a.tmpl) throw std::invalid_argument(std::string(where) + ": argument 'actor.tmpl' is null");
    if (a.clip < 0 || static_cast<std::size_t>(a.clip) >= a.tmpl->clips().size())
        throw std::invalid_argument(std::string(where) + ": template '" + a.tmpl->name() + "' has no clip " +
                                    std::to_string(a.clip));
    requireFinite(a.timeOffset, where, "actor.timeOffset");
    requireFinite(a.timeScale, where, "actor.timeScale");
    requireFinite(a.position, where, "actor.position");
    requireFinite(a.heading, where, "actor.heading");
    requireFinite(a.pathRadius, where, "actor.pathRadius");
    requireFinite(a.pathSpeed, where, "actor.pathSpeed");
    if (a.pathRadius < 0.0) throw std::invalid_argument(std::string(where) + ": argument 'actor.pathRadius' is negative");

    // Extent of the Skeleton Root relative to the Reference Point: sample the clip densely (cubic
    // splines can overshoot their keys), with 1 cm to spare. It depends on the clip only.
    const AnimationClip& clip = *a.tmpl->clips()[static_cast<std::size_t>(a.clip)];
    if (const auto cached = clipExtents_.find(&clip); cached != clipExtents_.end()) {
        actors_.push_back(a);
        extents_.push_back(cached->second);
        return static_cast<std::uint32_t>(actors_.size() - 1);
    }
    BoundingSphere extent(Vec3(0.0), 0.0);
    const auto steps = static_cast<std::size_t>(std::ceil(clip.duration() * 240.0));
    for (std::size_t k = 0; k <= steps; ++k)
        extent.expandBy(Vec3(clip.sampleRoot(steps ? clip.duration() * double(k) / double(steps) : 0.0, false).translation));
    for (const ClipChannel& c : clip.channels())
        if (c.target == ClipChannel::Target::RootTranslation)
            for (float t : c.times) extent.expandBy(Vec3(clip.sampleRoot(t, false).translation));
    extent.inflate(0.01);
    clipExtents_.emplace(&clip, extent);

    actors_.push_back(a);
    extents_.push_back(extent);
    return static_cast<std::uint32_t>(actors_.size() - 1);
}

const AnimationClip& KeyframeBehaviour::clipOf(std::uint32_t slot) const {
    const Actor& a = actors_[slot];
    return *a.tmpl->clips()[static_cast<std::size_t>(a.clip)];
}

Mat4 KeyframeBehaviour::referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) {
    const Actor& a = actors_[slot];
    return RefpointPath{a.position, a.heading, a.pathRadius, a.pathSpeed}.at(context.time, ops);
}

void KeyframeBehaviour::referencePoints(std::span<const std::uint32_t> slots, const FrameContext& context, OpTally* ops,
                                        std::span<Mat4> out) {
    constexpr std::size_t kBlock = 16;
    RefpointPath paths[kBlock];
    for (std::size_t first = 0; first < slots.size(); first += kBlock) {
        const std::size_t n = std::min(kBlock, slots.size() - first);
        for (std::size_t k = 0; k < n; ++k) {
            const Actor& a = actors_[slots[first + k]];
            paths[k] = RefpointPath{a.position, a.heading, a.pathRadius, a.pathSpeed};
        }
        RefpointPath::atEach({paths, n}, context.time, out.subspan(first, n), ops);
    }
}

double KeyframeBehaviour::clipTime(std::uint32_t slot, double time) const {
    const Actor& a = actors_[slot];
    return time * a.timeScale + a.timeOffset;
}

RootPose KeyframeBehaviour::skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) {
    const Actor& a = actors_[slot];
    if (level >= static_cast<int>(levelEnds_.size())) return RootPose{};
    return clipOf(slot).sampleRoot(time * a.timeScale + a.timeOffset, true, ops, level >= 1);
}

void KeyframeBehaviour::pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
                             std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) {
    const Actor& a = actors_[slot];
    if (level >= static_cast<int>(levelEnds_.size())) {  // beyond the last band: rest pose
        writeRestPose(tmpl, active, dofs);
        return;
    }
    clipOf(slot).sample(tmpl, time * a.timeScale + a.timeOffset, true, active, dofs, ops, level >= 1);
}

}  // namespace throng
