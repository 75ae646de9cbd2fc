#pragma once
// A flock flying over the town (boids: cohesion, alignment, separation, kept inside an area and an
// altitude band, with a little wander). Every bird is stepped once per frame from the previous
// frame's state, neighbours found in a grid walked in a fixed order, so the result depends neither
// on update order nor on thread count. Wings beat with the template's clip.

#include <limits>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "throng/actors/Behaviour.h"
#include "throng/sim/EffectCounters.h"

namespace throng::sim {

/// Boids for many birds.
class Flock : public Behaviour {
public:
    /// The flock's space and manners.
    struct Settings {
        glm::dvec2 center{0.0};          ///< centre of the area they fly over (x, z)
        glm::dvec2 size{200.0};          ///< its size
        glm::dvec2 altitude{25.0, 40.0}; ///< height band, metres
        glm::dvec2 speed{6.0, 11.0};     ///< airspeed range, m/s
        double neighbourRadius = 8.0;    ///< how far a bird heeds others
        double separation = 2.0;         ///< how close is too close
        std::uint64_t seed = 1;          ///< starting places and wander
    };
    /// One bird.
    struct Bird {
        std::shared_ptr<const ActorTemplate> tmpl;  ///< required; its clip `flapClip` beats the wings
        int flapClip = 0;                           ///< index of that clip in the template (looped)
        std::uint64_t stream = 0;                   ///< its random stream
    };

    /// A flock with the given level bands (default: wings beat smoothly within 60 m), counting into `counters`.
    explicit Flock(Settings settings, std::vector<double> levelEnds = {60.0, std::numeric_limits<double>::infinity()},
                   EffectCounters* counters = nullptr);

    /// Adds a bird before the first frame; returns its slot. Throws std::invalid_argument on a
    /// missing template or clip, or once the flock has started.
    std::uint32_t addBird(const Bird& bird);
    /// Position of a bird.
    glm::dvec3 position(std::uint32_t slot) const { return pos_[slot]; }

    std::span<const double> levelEnds() const override { return levelEnds_; }
    void advance(const FrameContext& context) override;
    Mat4 referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) override;
    RootPose skeletonRoot(std::uint32_t, double, int, OpTally*) override { return RootPose{}; }
    void pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
              std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) override;
    BoundingSphere skeletonRootExtent(std::uint32_t) const override { return BoundingSphere(Vec3(0.0), 0.0); }
    bool posesFromTemplateClips() const override { return true; }
    double clipTime(std::uint32_t slot, double time) const override;
    int mainClip(std::uint32_t slot) const override { return birds_[slot].flapClip; }
    std::size_t bytesPerSlot() const override { return sizeof(Bird) + 2 * sizeof(glm::dvec3) * 2; }

private:
    Settings settings_;
    std::vector<double> levelEnds_;
    EffectCounters* counters_;
    std::vector<Bird> birds_;
    std::vector<glm::dvec3> pos_, vel_, nextPos_, nextVel_;
    std::vector<std::uint32_t> cellStart_, cellFill_, cellBirds_, birdCell_;
    std::uint64_t steps_ = 0;
    bool started_ = false;
};

}  // namespace throng::sim
