#pragma once
// The surface-proxy warp (ProxyWarp.h) in the GL's vertex and fragment stages, as seed 003 §4.1
// warps its feature meshes: the proxy's triangles are drawn at the target pose, each vertex
// carrying where the same surface point lies in every source cell, depth-tested so that the nearer
// limb wins; a depth pass per source at the source's pose tells the fragment stage whether that
// source sees the point (a source that does not is not trusted there). It computes what warpProxy()
// computes, with the same premultiplied bilinear sampling done by hand, so the two differ only
// where the GL's rasterisation rule and the CPU's disagree on a triangle's edge pixels, and by
// rounding.

#include <memory>
#include <span>

#include <glm/vec3.hpp>

#include "throng/render/ProxyWarp.h"
#include "throng/scenegraph/Image.h"

namespace throng {

class GlContext;

/// Warps impostor cells through their proxy on the GPU of a GlContext and reads the result back.
class GpuProxyWarper {
public:
    /// Most sources one warp may read (the three views of a cell and more key-frames fit).
    static constexpr std::size_t kMaxSources = 4;

    /// Compiles the depth and warp programs in `context`. Throws std::invalid_argument if it is
    /// null and std::runtime_error with the compiler's log if a shader fails.
    explicit GpuProxyWarper(std::shared_ptr<GlContext> context);
    ~GpuProxyWarper();
    GpuProxyWarper(const GpuProxyWarper&) = delete;
    GpuProxyWarper& operator=(const GpuProxyWarper&) = delete;

    /// Same contract and result as warpProxy() (its argument errors), for at most kMaxSources
    /// sources and options without a rim, normal weighting or bicubic sampling (each refused with
    /// std::invalid_argument naming it); std::runtime_error if the GL cannot draw.
    Image warp(const ProxyMesh& mesh, std::span<const ProxySource> sources, const glm::vec3& toEye, double keyframe,
               const ProxyWarpOptions& options = {});

    /// A source of warpInto(): a layer of a texture array, and what it shows.
    struct LayerSource {
        int layer = 0;                      ///< its layer
        glm::vec3 toEye{0.0f, 0.0f, 1.0f};  ///< the direction it was baked from
        int keyframe = 0;                   ///< the key-frame it shows
        float weight = 1.0f;                ///< its share of the blend
    };

    /// The same warp without leaving the GL: the sources are layers of the RGBA8 2-D array texture
    /// `cells` (cells of mesh.cellSize() pixels, rows top first, as atlases store them), and the
    /// result is drawn and copied by the GL into layer `targetLayer` of the RGBA8 2-D array
    /// `target` (which may be `cells`); nothing is uploaded or read back. Texture names belong to
    /// this warper's context. Throws std::invalid_argument as warp() does, and for a zero name or
    /// a layer that does not fit; std::runtime_error if the GL cannot draw.
    void warpInto(const ProxyMesh& mesh, unsigned cells, std::span<const LayerSource> sources, const glm::vec3& toEye, double keyframe,
                  unsigned target, int targetLayer, const ProxyWarpOptions& options = {});

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
