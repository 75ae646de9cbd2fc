#pragma once
// A procedural walk for any template: every rotation DOF swings with a periodic signal within its
// limits and the Skeleton Root bobs, while the Reference Point walks a circle (closed form). Two
// precision levels: level 0 sums three harmonics per DOF with a secondary bob; level 1 keeps the
// fundamental only and no bob, for a quarter of the work. Poses are not clips, so actors driven by
// it are bounded by the template's reach radius.

#include <limits>
#include <vector>

#include "throng/actors/Behaviour.h"

namespace throng {

/// Procedural walking for many actors.
class ProceduralGait : public Behaviour {
public:
    /// One actor's parameters.
    struct Actor {
        Vec3 center{0.0};        ///< centre of the walking circle, parent frame
        double radius = 5.0;     ///< circle radius, metres (0: walk on the spot)
        double speed = 1.3;      ///< metres per second
        double phase = 0.0;      ///< starting angle on the circle and in the stride, radians
        double stepFrequency = 1.8;  ///< strides per second
    };

    /// A behaviour with the given level bands (default: precise within 40 m, simple beyond).
    explicit ProceduralGait(std::vector<double> levelEnds = {40.0, std::numeric_limits<double>::infinity()});

    /// Registers an actor; returns its slot. Throws std::invalid_argument on non-finite or negative values.
    std::uint32_t addActor(const Actor& actor);

    std::span<const double> levelEnds() const override { return levelEnds_; }
    Mat4 referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) override;
    /// Every slot's path at once (RefpointPath::atEach): the same matrices, sines taken in pairs.
    void referencePoints(std::span<const std::uint32_t> slots, const FrameContext& context, OpTally* ops,
                         std::span<Mat4> out) override;
    RootPose skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) override;
    void pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
              std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) override;
    BoundingSphere skeletonRootExtent(std::uint32_t slot) const override;
    std::size_t bytesPerSlot() const override { return sizeof(Actor); }
    bool posesFromTemplateClips() const override { return false; }

    /// Height of the Skeleton Root bob at level 0 (metres).
    static constexpr double kBobHeight = 0.03;

private:
    std::vector<double> levelEnds_;
    std::vector<Actor> actors_;
};

}  // namespace throng
