#pragma once
// Similarity of an approximate image to a reference, for measuring impostor morphing (seed 000
// Table 2 reports cross-correlation): normalised cross-correlation and SSIM, both restricted to
// where either image shows something (alpha > 0), so a large empty background cannot inflate them.

#include "throng/scenegraph/Image.h"

namespace throng::testkit {

/// Normalised cross-correlation (Pearson) of the four channels of `a` and `b` over the pixels
/// where either has alpha > 0 (over every pixel when `coveredOnly` is false, as a plain 2-D
/// correlation of the cells does): 1 for identical images, 0 for unrelated ones. 1 if both are
/// empty; 0 if one of them is constant over the region. Throws std::invalid_argument if an image
/// is invalid or the sizes differ.
double normalizedCrossCorrelation(const Image& a, const Image& b, bool coveredOnly = true);

/// Mean SSIM (Wang et al. 2004, 8 x 8 windows every 4 pixels, luminance of the premultiplied
/// colour) over the windows touching a pixel with alpha > 0 in either image; 1 if there is none.
/// Throws like normalizedCrossCorrelation().
double structuralSimilarity(const Image& a, const Image& b);

}  // namespace throng::testkit
