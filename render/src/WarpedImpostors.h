#pragma once
// Private to ImpostorRenderer: impostors drawn as their surface proxy (seed 003 §4.1's warp in the
// vertex stage). Each impostor is the template's ProxyMesh posed at its exact clip time, placed by
// its actor's transform and seen from the real eye; every vertex carries its place in each of the
// three view cells the quad would blend (stored, regenerated in the pool, or a fallback), so the
// fragment stage samples those cells where the surface lands in them, trusting a cell only where
// the surface is the nearest there (a depth layer beside every colour layer: the CPU warp's
// occlusion rule). One instanced call per atlas.

#include <cstdint>
#include <memory>
#include <span>

#include <glm/mat4x4.hpp>

namespace throng {

class GlContext;
class ImpostorAtlas;
class ShaderProgram;

/// What one warped impostor needs (per-instance attributes, floats).
struct WarpedInstance {
    float originPhase[4];  ///< actor origin relative to the eye (metres), then the clip phase in key-frames
    float axisX[3];        ///< the actor transform's columns (scale included)
    float axisY[3];
    float axisZ[3];
    float layers[3];       ///< colour (and depth) layer of each source cell
    float keyframes[3];    ///< key-frame each source cell shows
    float weights[3];      ///< each source's share (sum 1; 0: unused)
    float tint[4];         ///< the actor's tint
    float axes[18];        ///< each source cell's view: its image's right and up axes (viewBasis)
    float regionLayers[3]; ///< each source cell's region map (atlases with body regions)
    std::uint32_t look[4]; ///< the actor's BodyLook
};

/// One atlas's proxy on the GPU: positions per key-frame, triangles, view bases, depth layers.
struct WarpedAtlasGpu {
    unsigned positions = 0;  ///< RGB32F 2-D texture: x vertex, y key-frame
    unsigned bases = 0;      ///< RGB32F 2-D texture: x view, y 0 right, 1 up, 2 towards the eye
    unsigned triangles = 0;  ///< element buffer
    unsigned depths = 0;     ///< R32F 2-D array: the proxy's nearest depth in each colour layer's cell
    int indexCount = 0;      ///< indices in `triangles`
    int keyframes = 0;       ///< key-frames of the proxy
    int layers = 0;          ///< layers of `depths`
    std::size_t bytes = 0;   ///< of the positions, view bases and triangles
};

/// The programs and framebuffer that draw warped impostors and their depth layers.
class WarpedImpostorPass {
public:
    /// Compiles the programs in `context` (current). Throws std::runtime_error with the log if a
    /// shader fails.
    explicit WarpedImpostorPass(GlContext& context);
    ~WarpedImpostorPass();
    WarpedImpostorPass(const WarpedImpostorPass&) = delete;
    WarpedImpostorPass& operator=(const WarpedImpostorPass&) = delete;

    /// Uploads `atlas`'s proxy (it must have one) with `layers` depth layers, all empty.
    WarpedAtlasGpu upload(const ImpostorAtlas& atlas, int layers);
    /// Frees what upload() made.
    void release(WarpedAtlasGpu& gpu);
    /// Fills depth layer `layer` with the proxy of `atlas` at key-frame `keyframe` seen from view
    /// `view`: what the colour layer of that cell shows.
    void depthInto(const ImpostorAtlas& atlas, WarpedAtlasGpu& gpu, int layer, std::uint32_t view, int keyframe);
    /// Fills `w.axes` from the views of its three sources.
    static void setViews(const ImpostorAtlas& atlas, WarpedInstance& w, const float views[3]);
    /// Draws `instances` of `atlas` from colour array `cells` into the bound framebuffer (depth
    /// test on), `viewRotationProjection` taking eye-relative positions to clip space; `regions`
    /// (0: none) is the atlas's region maps, one layer per cell, recoloured as the quads are.
    void draw(const ImpostorAtlas& atlas, const WarpedAtlasGpu& gpu, unsigned cells, unsigned regions,
              std::span<const WarpedInstance> instances, const glm::mat4& viewRotationProjection);

private:
    GlContext& context_;
    std::unique_ptr<ShaderProgram> warp_, depth_;
    unsigned vao_ = 0, instanceBuffer_ = 0, depthVao_ = 0, fbo_ = 0, depthBuffer_ = 0;
    int depthBufferSize_ = 0;
};

}  // namespace throng
