#pragma once
// Warping between impostor views instead of mixing their colours: the cells of the three views
// around an eye direction (ViewHemisphere::blend) are each warped toward the feature lines of the
// in-between view before they are blended. Where those target lines come from is what the seeds
// differ in:
//   - seed 003 §4.1: the barycentric interpolation of the three views' feature positions;
//   - seed 000 §5.1 (view morphing, Seitz and Dyer): the same interpolation between the views,
//     then a postwarp to the camera that looks from the eye. For orthographic impostor views the
//     prewarp is the identity (every linear blend of affine views is itself an affine view), and
//     the postwarp is the 2x2 map, about the cell centre, from the blended camera to the eye's;
//   - ours: the bones reprojected from the 3-D track (FeatureTrack::lines for the eye direction).
// CPU functions, for measuring; the run-time quad shader does not use them (yet).

#include <span>
#include <vector>

#include <glm/mat2x2.hpp>
#include <glm/vec3.hpp>

#include "throng/render/BeierNeely.h"
#include "throng/scenegraph/Image.h"

namespace throng {

class GpuMorpher;

/// Seed 003: the lines of several views blended point by point with `weights` (barycentric; they
/// are used as given). Throws std::invalid_argument if the counts of views and weights differ,
/// there is no view, or the views' line counts differ.
std::vector<FeatureLine> blendViewLines(std::span<const std::vector<FeatureLine>> views, std::span<const float> weights);

/// Seed 000's postwarp for orthographic views: the 2x2 map taking image offsets (x right, y down,
/// from the cell centre) of the camera blended from `viewDirections` with `weights` (its image
/// axes are the weighted sums of theirs) to those of the camera looking from `toEye`, by least
/// squares. Identity when the weights pick one view and `toEye` is that view. Throws
/// std::invalid_argument on a count mismatch, no view, or a vertical or non-finite direction.
glm::mat2 viewPostwarp(std::span<const glm::vec3> viewDirections, std::span<const float> weights, const glm::vec3& toEye);

/// `lines` with every end point mapped by `m` about the centre of a `cellSize` pixel cell.
std::vector<FeatureLine> postwarpLines(std::span<const FeatureLine> lines, const glm::mat2& m, int cellSize);

/// Each of `cells` warped from its `lines` to `target` (Beier-Neely, with `attributes` for the
/// target lines, see morphImages) and the results blended with `weights` (premultiplied, weights
/// renormalised; cells of weight 0 are skipped). On `gpu` when given and the lines fit it. Throws
/// std::invalid_argument on count or size mismatches, no cell, or weights that are negative, not
/// finite or sum to zero.
Image warpViews(std::span<const Image> cells, std::span<const std::vector<FeatureLine>> lines, std::span<const float> weights,
                std::span<const FeatureLine> target, const MorphParameters& parameters = {},
                std::span<const LineAttributes> attributes = {}, GpuMorpher* gpu = nullptr);

}  // namespace throng
