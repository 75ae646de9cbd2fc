#pragma once
// Occlusion-aware morphing of an impostor cell. Both stored neighbours are warped toward the
// in-between with limb-aware features (MorphFeatures), and the cross-dissolve then trusts, pixel by
// pixel, the neighbour whose warped sample shows the limb the in-between shows there: where a limb
// crossed in front of another in one neighbour, that neighbour's sample is of the wrong limb and
// the other neighbour fills in. Limbs are told apart by their capsules and depths (FeatureTrack),
// so no extra image (ID or depth buffer) is stored.

#include <span>

#include <glm/vec2.hpp>

#include "throng/render/BeierNeely.h"
#include "throng/render/FeatureTrack.h"
#include "throng/render/MorphFeatures.h"
#include "throng/scenegraph/Image.h"

namespace throng {

/// How much a neighbour is trusted where its sample shows another limb.
struct VisibilityOptions {
    /// Weight (relative to 1) of a neighbour whose sample shows a limb unrelated to the one in
    /// front in the in-between; 1 gives the plain cross-dissolve.
    float distrust = 0.02f;
    /// Capsule radius (over the feature's radius) within which a pixel counts as the limb's flesh.
    float reach = 1.0f;
};

/// Index (into `lines`) of the feature whose flesh is in front at `x`: among the primary features
/// (`primary[i]` != 0) with a positive radius whose capsule (radius times `reach`) holds `x`, the
/// one nearest the eye at its closest point; -1 if none holds it. Spans must have equal sizes.
int frontFeature(glm::vec2 x, std::span<const FeatureLine> lines, std::span<const LineAttributes> attributes,
                 std::span<const std::uint8_t> primary, float reach = 1.0f);

/// The in-between at `t` of `from` and `to` with features `f` (capsule radii and depths filled, as
/// droppedCellFeatures() gives them): warped as morphImages() warps them (with f.targetAttributes),
/// then blended with each neighbour's weight cut to `visibility.distrust` where its sample's front
/// limb is not related (FeatureTrack::related) to the in-between's front limb. `threads` > 1 splits
/// rows (same result). Throws std::invalid_argument as morphImages() does, and if the feature
/// arrays of `f` differ in size or name a bone outside `track`.
Image morphLimbs(const Image& from, const Image& to, const CellFeatures& f, const FeatureTrack& track, float t,
                 const MorphParameters& parameters = {}, const VisibilityOptions& visibility = {}, unsigned threads = 1);

}  // namespace throng
