#pragma once
// Beier-Neely morphing with the warp evaluated on a coarse grid (field morphing's mesh
// approximation): the source position of every grid vertex is computed exactly from the feature
// lines and interpolated bilinearly for the pixels between, so a cell costs about step^2 fewer
// line evaluations. The warp is smooth away from line ends, so the image changes little; its error
// against morphImages() is measured (throng-impostor-quality, bench_impostor_frame), never assumed.

#include <span>

#include "throng/render/BeierNeely.h"
#include "throng/scenegraph/Image.h"

namespace throng {

/// The in-between image of morphImages() with the warp sampled every `step` pixels (pixel centres
/// of columns and rows 0, step, 2 step, ..., and the last one) and interpolated bilinearly between;
/// `step` <= 1 is morphImages() itself. Same sampling and cross-dissolve. Throws as morphImages().
Image morphImagesOnGrid(const Image& from, std::span<const FeatureLine> fromLines, const Image& to,
                        std::span<const FeatureLine> toLines, std::span<const FeatureLine> targetLines, float t,
                        const MorphParameters& parameters, int step);

}  // namespace throng
