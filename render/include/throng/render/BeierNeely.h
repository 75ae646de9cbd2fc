#pragma once
// Feature-based image metamorphosis (Beier and Neely 1992), the CPU reference: an in-between
// image of two key-frames is made by warping both toward intermediate feature lines and
// cross-dissolving them (seed 000 §4-5). Images are premultiplied RGBA8 (impostor cells are baked
// over transparent black), so bilinear sampling at silhouettes does not bleed the background.
// GpuMorpher computes the same thing in a fragment shader; the pixel arithmetic here mirrors its
// GLSL operation for operation so the two agree to rounding.

#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "throng/scenegraph/Image.h"

namespace throng {

/// A directed feature line segment from `p` to `q`, in pixels of its image (x right, y down, pixel
/// centres at +0.5).
struct FeatureLine {
    glm::vec2 p{0.0f};  ///< start point
    glm::vec2 q{0.0f};  ///< end point
};

/// The three constants of Beier-Neely line weights: weight = (length^p / (a + distance))^b.
struct MorphParameters {
    // Defaults chosen by a sweep on CesiumMan and robot (throng-impostor-quality --a --b --p):
    // small a and large b keep each limb's warp local to its own bone, which removes most ghosting.
    float a = 0.5f;  ///< pixels; > 0 keeps weights finite on a line (clamped to 1e-3 on use)
    float b = 2.5f;  ///< how fast weight falls with distance (0.5-2 in Beier-Neely; higher is more local)
    float p = 0.5f;  ///< how much longer lines weigh more (0-1)
    /// Depth order (used only with LineAttributes): where a pixel lies inside a line's capsule, the
    /// line's weight is multiplied by exp(depth * z), z its depth toward the eye (pixels, >= 0 above
    /// the farthest feature) at the point nearest the pixel, so where two limbs overlap the nearer
    /// one carries the warp. 0: no depth order. 1/pixel.
    float depth = 0.0f;
};

/// Per-line extras of the limb-aware warp; an empty span of them gives the classic weights.
struct LineAttributes {
    float weight = 1.0f;  ///< multiplies the line's weight (importance)
    /// Pixels: distance is measured from a capsule of this radius around the line (the limb's
    /// flesh), so every pixel of a limb follows its own bone rather than the nearest axis.
    float radius = 0.0f;
    float depthP = 0.0f;  ///< depth toward the eye at `p` (pixels above the farthest feature)
    float depthQ = 0.0f;  ///< depth toward the eye at `q` (pixels)
};

/// Bound on |depth * z| in the depth factor, so weights stay finite in float.
constexpr float kMaxDepthExponent = 40.0f;

/// Lines shorter than this (pixels) are treated as point features: they translate their
/// neighbourhood and weigh as a line of kMinFeatureLength pixels.
constexpr float kDegenerateFeatureLength = 1e-3f;
/// Length (pixels) below which a line's length no longer reduces its weight.
constexpr float kMinFeatureLength = 1.0f;

/// Position `x` (pixels) in the destination maps to the returned position in the source, given
/// corresponding lines (`destination[i]` is where `source[i]` goes). Spans must have equal sizes;
/// with no line (or all weights zero) the position is unchanged. Always finite for finite input.
/// `attributes` (empty, or one per line, describing the destination lines) add per-line weights,
/// capsule radii and depth order; empty gives exactly the classic Beier-Neely weights.
glm::vec2 beierNeelySourcePosition(glm::vec2 x, std::span<const FeatureLine> destination,
                                   std::span<const FeatureLine> source, const MorphParameters& parameters,
                                   std::span<const LineAttributes> attributes = {});

/// Lines at fraction `t` between `a` and `b` (endpoints interpolated), written to `out` (resized).
/// Throws std::invalid_argument if the sizes of `a` and `b` differ.
void interpolateLines(std::span<const FeatureLine> a, std::span<const FeatureLine> b, float t,
                      std::vector<FeatureLine>& out);

/// Premultiplied RGBA sample of `image` at `position` (pixels), bilinear, transparent outside.
/// Writes four values in [0, 1] to `rgba`.
void samplePremultiplied(const Image& image, glm::vec2 position, float rgba[4]);

/// The in-between image at fraction `t` (0: `from`, 1: `to`): `from` warped from `fromLines` to
/// `targetLines`, `to` warped from `toLines` to `targetLines`, cross-dissolved by `t`. The result
/// has the size of `from`. `threads` > 1 splits rows among threads (same result). `attributes`
/// (empty or one per line) describe the target lines (see beierNeelySourcePosition). Throws
/// std::invalid_argument if an image is invalid, sizes differ, line or attribute counts differ, an
/// attribute is not finite (or a radius or weight negative) or `t` is not finite.
Image morphImages(const Image& from, std::span<const FeatureLine> fromLines, const Image& to,
                  std::span<const FeatureLine> toLines, std::span<const FeatureLine> targetLines, float t,
                  const MorphParameters& parameters = {}, unsigned threads = 1,
                  std::span<const LineAttributes> attributes = {});

/// Throws std::invalid_argument naming `who` if `attributes` is neither empty nor one per line
/// (`lines`), or an attribute is not finite, or a weight or radius is negative.
void checkLineAttributes(std::span<const LineAttributes> attributes, std::size_t lines, const char* who);

}  // namespace throng
