#pragma once
// Automatic features for morphing an impostor cell, from the skeleton itself (FeatureTrack): the
// bones seen from the cell's view in both stored neighbours and at the in-between time, plus what
// the classic bone lines lack where limbs overlap: per-line weights, capsule radii (each limb's
// flesh follows its own bone), depth toward the eye (the nearer limb carries the warp) and extra
// point or silhouette features. No hand-picked line anywhere.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "throng/render/BeierNeely.h"
#include "throng/render/FeatureTrack.h"

namespace throng {

class ImpostorAtlas;

/// How much each bone's line weighs.
enum class LineWeighting {
    Uniform,  ///< every line 1 (the classic warp)
    Length,   ///< the bone's 3-D length over the mean length
    Motion,   ///< how far the bone moves between the two stored neighbours, over the mean (plus 0.1)
};

/// Features added beside each bone's line.
enum class ExtraFeatures {
    None,         ///< bone lines only
    Midpoints,    ///< a point feature at each bone's middle
    JointPoints,  ///< point features at each bone's two ends and middle
    Silhouettes,  ///< two lines along the limb's outline, one radius either side of the bone
};

/// What features a morph uses.
struct FeatureOptions {
    std::size_t bones = 1000;                     ///< the strongest bones of the atlas (all when larger)
    LineWeighting weighting = LineWeighting::Uniform;  ///< per-line weights
    float weightExponent = 1.0f;                  ///< weights are raised to this power
    bool capsules = false;                        ///< measure distance from each limb's flesh, not its axis
    float radiusScale = 1.0f;                     ///< capsule radius over the measured flesh radius
    ExtraFeatures extra = ExtraFeatures::None;    ///< extra features per bone
};

/// Corresponding features of one morph: lines in both sources and the target, the attributes of
/// each set (depths differ with the pose), and the bone each feature comes from.
struct CellFeatures {
    /// \var from
    /// Lines in the stored neighbour before the key-frame, one per feature.
    /// \var to
    /// Lines in the stored neighbour after it, one per feature.
    std::vector<FeatureLine> from, to, target;                            ///< one per feature
    /// \var fromAttributes
    /// Attributes of the `from` lines, one per feature.
    /// \var toAttributes
    /// Attributes of the `to` lines, one per feature.
    std::vector<LineAttributes> fromAttributes, toAttributes, targetAttributes;  ///< one per feature
    std::vector<std::uint32_t> bones;                                     ///< bone of each feature
    std::vector<std::uint8_t> primary;                                    ///< 1 for a bone's own line
};

/// The features of the bones `bones` of key-frame `keyframe` seen from `toEye`, weighted by
/// `weights` (one per bone of the track): lines and attributes in the same order as
/// cellFeatures(). Throws std::invalid_argument for an unknown bone or a weight count mismatch.
void viewFeatures(const FeatureTrack& track, int keyframe, const glm::vec3& toEye, std::span<const std::uint32_t> bones,
                  std::span<const float> weights, const FeatureOptions& options, std::vector<FeatureLine>& lines,
                  std::vector<LineAttributes>& attributes);

/// Per-bone weights (one per bone of the track) for a morph between key-frames `before` and
/// `after` under `options.weighting` and `options.weightExponent`.
std::vector<float> boneWeights(const FeatureTrack& track, int before, int after, const FeatureOptions& options);

/// The features for regenerating dropped key-frame `keyframe` of `atlas` in view `view` from its
/// stored neighbours, with the target at the skeleton's own pose. Throws std::invalid_argument if
/// the key-frame is stored or out of range, the view is out of range, or the track does not match
/// the atlas (bones, key-frames).
CellFeatures droppedCellFeatures(const ImpostorAtlas& atlas, const FeatureTrack& track, std::uint32_t view, int keyframe,
                                 const FeatureOptions& options);

}  // namespace throng
