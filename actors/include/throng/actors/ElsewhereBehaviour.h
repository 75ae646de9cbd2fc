#pragma once
// Actors another process of the run simulates and shows: a process that poses only its share of a
// crowd (a rank posing the walkers it steps) still holds every actor of the scene, so that its
// nodes and numbers are the drawing process's, but the others' actors are never present here.
// Nothing is computed for them: phase 1 visits none, CULL 1 rejects them unread.

#include <cstdint>
#include <vector>

#include "throng/actors/Behaviour.h"

namespace throng {

/// A behaviour whose actors are all absent from this process.
class ElsewhereBehaviour : public Behaviour {
public:
    /// Stand-ins for actors whose own behaviour has the level bands `levelEnds`.
    explicit ElsewhereBehaviour(std::vector<double> levelEnds) : levelEnds_(std::move(levelEnds)) {}

    /// Registers one more actor; returns its slot.
    std::uint32_t addActor() { return slots_++; }
    /// Number of actors.
    std::uint32_t size() const { return slots_; }

    std::span<const double> levelEnds() const override { return levelEnds_; }
    /// Never called for an absent actor: throws std::logic_error.
    Mat4 referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) override;
    /// Never called for an absent actor: throws std::logic_error.
    RootPose skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) override;
    /// Never called for an absent actor: throws std::logic_error.
    void pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl, std::span<const std::uint8_t> active,
              std::span<float> dofs, OpTally* ops) override;
    /// The Reference Point itself (the stand-in never moves a Skeleton Root).
    BoundingSphere skeletonRootExtent(std::uint32_t) const override { return BoundingSphere(Vec3(0.0), 0.0); }
    /// True: the sphere the crowd computes from the clips is never used here, and needs no other bound.
    bool posesFromTemplateClips() const override { return true; }
    bool presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const override;
    std::optional<std::span<const std::uint32_t>> presentSlots() const override { return std::span<const std::uint32_t>(); }
    bool known(std::uint32_t) const override { return false; }
    std::size_t bytesPerSlot() const override { return 0; }

private:
    std::vector<double> levelEnds_;
    std::uint32_t slots_ = 0;
};

}  // namespace throng
