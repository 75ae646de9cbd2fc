#pragma once
// Binary silhouettes for the picture oracle: the covered pixels of a rendered frame, and an
// independent CPU rasterisation of a triangle mesh seen by a camera, compared by intersection over
// union. The rasteriser shares nothing with GlRenderer but the camera's matrices: it projects each
// vertex with Camera::viewProjection() and covers a pixel when its centre lies inside a projected
// triangle (either facing), as OpenGL samples a pixel at its centre.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/ext/vector_uint3_sized.hpp>
#include <glm/vec3.hpp>

#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Image.h"

namespace throng::test {

/// A binary mask, rows top first (as Image).
struct Mask {
    int width = 0;                      ///< pixels
    int height = 0;                     ///< pixels
    std::vector<std::uint8_t> covered;  ///< 1 where covered, width * height entries

    /// Number of covered pixels.
    std::size_t count() const;
};

/// Pixels of `image` whose colour differs from `clear` by more than `tolerance` in some channel.
Mask silhouetteOf(const Image& image, glm::u8vec3 clear, int tolerance = 2);

/// Pixels whose centre lies inside the projection of some triangle (three indices into
/// `positions` each, world space) seen by `camera`, in a width x height frame. Throws
/// std::invalid_argument if a vertex lies outside the camera's near and far planes (the oracle
/// does not clip) or an index is out of range.
Mask rasterise(std::span<const glm::dvec3> positions, std::span<const std::uint32_t> triangles, const Camera& camera,
               int width, int height);

/// |a and b| / |a or b| (1 when both are empty). Throws std::invalid_argument if the sizes differ.
double intersectionOverUnion(const Mask& a, const Mask& b);

/// An image of two masks for a human: grey where both cover, red where only `a`, blue where only
/// `b`, black elsewhere.
Image maskDifference(const Mask& a, const Mask& b);

}  // namespace throng::test
