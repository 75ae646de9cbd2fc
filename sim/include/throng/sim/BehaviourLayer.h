#pragma once
// A behaviour layered over another (gaze, faces): it changes the pose and adds bands of its own,
// and forwards everything else to the base, mapping its levels (its bands merged with the base's)
// to the base's.

#include <memory>
#include <span>
#include <vector>

#include "throng/actors/Behaviour.h"

namespace throng::sim {

/// The forwarding half of a layer over a base behaviour.
class BehaviourLayer : public Behaviour {
public:
    std::span<const double> levelEnds() const override { return ends_; }
    Mat4 referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) override {
        return base_->referencePoint(slot, context, ops);
    }
    /// The base behaviour's, batched as it batches them.
    void referencePoints(std::span<const std::uint32_t> slots, const FrameContext& context, OpTally* ops,
                         std::span<Mat4> out) override {
        base_->referencePoints(slots, context, ops, out);
    }
    RootPose skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) override {
        return base_->skeletonRoot(slot, time, baseLevel(level), ops);
    }
    BoundingSphere skeletonRootExtent(std::uint32_t slot) const override { return base_->skeletonRootExtent(slot); }
    bool posesFromTemplateClips() const override { return base_->posesFromTemplateClips(); }
    bool presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const override {
        return base_->presence(slots, present);
    }
    bool known(std::uint32_t slot) const override { return base_->known(slot); }
    bool steppingRegions(std::span<const std::uint32_t> slots, std::span<std::uint32_t> regions) const override {
        return base_->steppingRegions(slots, regions);
    }
    std::optional<std::span<const std::uint32_t>> presentSlots() const override { return base_->presentSlots(); }
    double poseMargin(std::uint32_t slot) const override { return base_->poseMargin(slot); }
    double clipTime(std::uint32_t slot, double time) const override { return base_->clipTime(slot, time); }
    int mainClip(std::uint32_t slot) const override { return base_->mainClip(slot); }

protected:
    /// A layer over `base`; throws std::invalid_argument naming `who` if it is null.
    BehaviourLayer(std::shared_ptr<Behaviour> base, const char* who);
    /// Merges the base's band ends with each of `own` (the layer's effects' band ends), records the
    /// base's level of every merged band, and returns a distance inside each merged band (its
    /// middle; beyond the last end, farther still), for the layer to find its own levels by.
    std::vector<double> mergeBands(const std::vector<std::vector<double>>& own);
    /// The base's level of merged level `level`.
    int baseLevel(int level) const { return baseLevel_[std::size_t(level)]; }
    /// Puts every DOF value of node `node` of `tmpl` (none when negative) back at its rest value.
    /// An actor's DOF values persist from frame to frame and a base behaviour writes only what its
    /// clip keys: what a layer changed last frame must not carry over into this one's.
    static void restNode(const ActorTemplate& tmpl, int node, std::span<float> dofs);

    std::shared_ptr<Behaviour> base_;  ///< the behaviour layered over

private:
    std::vector<double> ends_;
    std::vector<int> baseLevel_;
};

}  // namespace throng::sim
