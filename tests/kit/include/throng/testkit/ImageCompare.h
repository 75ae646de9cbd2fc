#pragma once
// How far two images are apart: for golden-image tests and for measuring the quality of
// approximations (impostors, LOD) against a full-detail render.

#include <cstddef>

#include "throng/scenegraph/Image.h"

namespace throng::testkit {

/// Differences between two images of the same size, over all four channels.
struct ImageDifference {
    int maxChannelDifference = 0;        ///< largest |a - b| of any channel of any pixel (0-255)
    std::size_t pixelsOverThreshold = 0; ///< pixels with some channel differing by more than the threshold
    double fractionOverThreshold = 0;    ///< pixelsOverThreshold / pixel count
    double meanAbsoluteDifference = 0;   ///< mean |a - b| over all channels (0-255)
    double psnr = 0;                     ///< peak signal-to-noise ratio in dB (infinity when identical)
};

/// Compares `a` and `b` channel by channel; a pixel counts as different when one of its channels
/// differs by more than `threshold`. Throws std::invalid_argument if an image is invalid, the sizes
/// differ or `threshold` is outside 0-255.
ImageDifference compareImages(const Image& a, const Image& b, int threshold = 0);

/// An image showing where `a` and `b` differ: |a - b| per channel, scaled by `gain` and clamped,
/// opaque. For writing next to a failed test. Throws like compareImages().
Image differenceImage(const Image& a, const Image& b, int gain = 8);

}  // namespace throng::testkit
