#pragma once
// Plays a template's key-framing tables (the seed's actors play them). Level 0 interpolates as the
// clip says; level 1 holds the previous key (cheaper, jerkier). The Reference Point stands still or
// travels a circle, in closed form, so trajectories never drift and never depend on the camera.

#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "throng/actors/Behaviour.h"

namespace throng {

class AnimationClip;

/// Key-frame playback for many actors.
class KeyframeBehaviour : public Behaviour {
public:
    /// One actor's parameters.
    struct Actor {
        std::shared_ptr<const ActorTemplate> tmpl;  ///< whose clip is played (required)
        int clip = 0;                 ///< clip index in the template
        double timeOffset = 0.0;      ///< seconds added to the frame time
        double timeScale = 1.0;       ///< playback speed
        Vec3 position{0.0};           ///< Reference Point (or centre of its circle), parent frame
        double heading = 0.0;         ///< radians about +Y
        double pathRadius = 0.0;      ///< > 0: the Reference Point travels a circle of this radius
        double pathSpeed = 0.0;       ///< ... at this speed (m/s), counter-clockwise seen from +Y
    };

    /// A behaviour with the given level bands (default: interpolate within 60 m, hold keys beyond).
    explicit KeyframeBehaviour(std::vector<double> levelEnds = {60.0, std::numeric_limits<double>::infinity()});

    /// Registers an actor; returns its slot. Throws std::invalid_argument if the template is null,
    /// the clip does not exist or a value is not finite.
    std::uint32_t addActor(const Actor& actor);

    std::span<const double> levelEnds() const override { return levelEnds_; }
    Mat4 referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) override;
    /// Every slot's path at once (RefpointPath::atEach): the same matrices, sines taken in pairs.
    void referencePoints(std::span<const std::uint32_t> slots, const FrameContext& context, OpTally* ops,
                         std::span<Mat4> out) override;
    RootPose skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) override;
    void pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
              std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) override;
    BoundingSphere skeletonRootExtent(std::uint32_t slot) const override { return extents_[slot]; }
    double clipTime(std::uint32_t slot, double time) const override;
    int mainClip(std::uint32_t slot) const override { return actors_[slot].clip; }
    std::size_t bytesPerSlot() const override { return sizeof(Actor) + sizeof(BoundingSphere); }
    bool posesFromTemplateClips() const override { return true; }

private:
    const AnimationClip& clipOf(std::uint32_t slot) const;
    std::vector<double> levelEnds_;
    std::vector<Actor> actors_;
    std::vector<BoundingSphere> extents_;
    std::map<const AnimationClip*, BoundingSphere> clipExtents_;  // the Skeleton Root's extent, per clip
};

}  // namespace throng
