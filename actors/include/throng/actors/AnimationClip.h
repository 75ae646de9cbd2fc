#pragma once
// A key-framing table (the seed's actors play them; glTF animations load into them): channels of
// keys driving DOFs of Skeleton nodes or the Skeleton Root, with step, linear or cubic-spline
// interpolation. Orientations interpolate along the shortest arc. Sampling is stateless: a pose is a
// function of time, never accumulated from frame to frame.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "throng/actors/RootPose.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

class ActorTemplate;

/// How values between keys are found.
enum class Interpolation : std::uint8_t {
    Step,         ///< the previous key's value
    Linear,       ///< straight line; spherical (shortest arc) for orientations
    CubicSpline,  ///< Hermite spline with per-key in and out tangents (glTF CUBICSPLINE)
};

/// One animated value: a DOF of a node, the Skeleton Root's translation or orientation, or the
/// weight of a morph channel (ActorTemplate::morphChannels).
struct ClipChannel {
    /// What the channel drives.
    enum class Target : std::uint8_t { NodeDof, RootTranslation, RootOrientation, MorphWeight };
    Target target = Target::NodeDof;        ///< what is driven
    std::uint32_t node = 0;                 ///< node index (NodeDof), morph channel index (MorphWeight)
    std::uint32_t dof = 0;                  ///< DOF index within the node (NodeDof)
    Interpolation interpolation = Interpolation::Linear;  ///< between keys
    std::vector<float> times;               ///< key times, seconds, strictly increasing, >= 0
    /// Key values: width floats per key (1, 3 or 4), or 3 * width per key for CubicSpline
    /// (in-tangent, value, out-tangent).
    std::vector<float> values;
};

/// A named set of channels.
class AnimationClip {
public:
    /// A clip; throws std::invalid_argument naming the clip and channel when times are not
    /// increasing or finite, values are not finite, or their count does not fit the keys.
    /// Widths are checked against a template when the clip is added to one.
    AnimationClip(std::string name, std::vector<ClipChannel> channels);

    /// Name.
    const std::string& name() const { return name_; }
    /// Time of the last key of any channel (seconds).
    double duration() const { return duration_; }
    /// Channels.
    const std::vector<ClipChannel>& channels() const { return channels_; }

    /// Samples the node and morph-weight channels at time `t` (wrapped into [0, duration) when
    /// `loop`, else clamped) into `dofs` (the DOF layout of `tmpl`, a template the clip was added
    /// to). Channels of nodes whose `active` flag is 0 are skipped (an empty `active` means every
    /// node). With `holdKeys`,
    /// every channel holds its previous key (cheaper, for far actors). Costs go to `ops`. Returns
    /// the number of values written.
    std::size_t sample(const ActorTemplate& tmpl, double t, bool loop, std::span<const std::uint8_t> active,
                       std::span<float> dofs, OpTally* ops = nullptr, bool holdKeys = false) const;
    /// Samples the Skeleton Root channels at time `t` (identity where the clip has none).
    RootPose sampleRoot(double t, bool loop, OpTally* ops = nullptr, bool holdKeys = false) const;

    /// Local time used for `t`: wrapped or clamped into [0, duration].
    double localTime(double t, bool loop) const;
    /// Per channel, the first channel with the very same key times (itself when none): channels
    /// that share a time source share the key search when sampled (glTF samplers often share
    /// their input accessor; procedural clips key every channel alike).
    std::span<const std::uint32_t> timeSources() const { return timeSources_; }

private:
    std::string name_;
    std::vector<ClipChannel> channels_;
    std::vector<std::uint32_t> timeSources_;
    double duration_ = 0.0;
};

/// Values per key of a channel whose target takes `width` floats (3x for CubicSpline).
constexpr std::size_t valuesPerKey(Interpolation interpolation, int width) {
    return static_cast<std::size_t>(interpolation == Interpolation::CubicSpline ? 3 * width : width);
}

}  // namespace throng
