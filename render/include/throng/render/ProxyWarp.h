#pragma once
// Warping impostor cells through the figure's own surface (ProxyMesh): the target cell (any
// key-frame, any eye direction) is rasterised from the proxy's triangles at the target pose, and
// each pixel fetches the same surface point from every stored source cell (other key-frames,
// other views), where the proxy at the source's pose puts it. Triangles are depth-tested, so the
// nearer limb wins where limbs overlap, and a source in which that point is hidden behind another
// part (its own depth buffer says so) is not trusted there. The runtime counterpart is seed 003's
// vertex stage: draw the proxy's triangles at target positions with source positions as texture
// coordinates.

#include <span>

#include <glm/vec3.hpp>

#include "throng/render/ProxyMesh.h"
#include "throng/scenegraph/Image.h"

namespace throng {

/// One stored cell a proxy warp reads.
struct ProxySource {
    const Image* image = nullptr;   ///< the cell (premultiplied RGBA, ProxyMesh::cellSize() square)
    glm::vec3 toEye{0.0f, 0.0f, 1.0f};  ///< the direction it was baked from
    int keyframe = 0;               ///< the key-frame it shows
    float weight = 1.0f;            ///< its share of the blend (1 - t and t, or barycentric weights)
};

/// How a proxy warp blends.
struct ProxyWarpOptions {
    /// Pixels: a surface point counts as visible in a source when it is within this of the
    /// source's nearest surface there.
    float depthTolerance = 2.0f;
    /// Weight (relative to 1) of a source where the point is hidden in it; 1 ignores visibility.
    float distrust = 0.0f;
    /// Pixels beyond the proxy's outline that still fetch (with the flow of the nearest covered
    /// pixel), so the sources' own anti-aliased outline, and parts a coarse proxy misses, come through.
    int rim = 0;
    /// How much a source is preferred where the surface faces the way it does in the target: its
    /// weight is multiplied by ((1 + cos angle between the two normals) / 2)^normalSharpness, so a
    /// source in which the surface turned (other shading, other foreshortening) counts less. 0: off.
    float normalSharpness = 0.0f;
    /// Sample the sources with a Catmull-Rom (bicubic) filter rather than bilinearly: sharper, since
    /// every warped pixel is resampled between texels.
    bool bicubic = false;
    /// Inside the proxy the figure is opaque: samples are weighted by their own alpha and the result
    /// is un-premultiplied to alpha 1, so texels beyond a source's outline (where the surface point
    /// sat at its edge) do not darken or thin the target. Off: the plain premultiplied blend.
    bool opaqueInside = false;
};

/// Checks a proxy warp's arguments as warpProxy() does (its std::invalid_argument messages, which
/// start with `who`); returns the sum of the sources' weights.
float checkProxyWarp(const ProxyMesh& mesh, std::span<const ProxySource> sources, double keyframe, const ProxyWarpOptions& options,
                     const char* who);

/// The cell at key-frame `keyframe` (fractional: any time of the looping clip, the proxy between
/// its key-frames) seen from `toEye`, warped from `sources` through `mesh` and blended by their
/// weights (renormalised where visibility removes some). Pixels neither covered by the proxy nor
/// within the rim are transparent. Throws std::invalid_argument if there is no source, a source
/// image is missing or not cellSize() square, a source key-frame is out of range, `keyframe` is
/// not finite, a weight is negative or not finite, or the weights sum to zero.
Image warpProxy(const ProxyMesh& mesh, std::span<const ProxySource> sources, const glm::vec3& toEye, double keyframe,
                const ProxyWarpOptions& options = {});

}  // namespace throng
