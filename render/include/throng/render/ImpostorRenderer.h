#pragma once
// Draws ImpostorBatcher's instances with OpenGL: camera-facing quads, one instanced call per atlas,
// each blending its three view cells by their weights in the fragment shader. An atlas's stored
// cells live in one 2-D array texture (a layer per cell, uploaded once); the morphed cells of the
// frame are uploaded into extra layers, once per cell whatever the number of actors showing it.
// Draw after GlRenderer::draw() and before endFrame(): quads are depth-tested against the meshes.

#include <cstdint>
#include <memory>
#include <span>

#include "throng/render/ImpostorBatcher.h"

namespace throng {

class Camera;
class GlContext;

/// What ImpostorRenderer did in the last draw().
struct ImpostorRenderStatistics {
    std::uint64_t drawCalls = 0;         ///< instanced calls
    std::uint64_t instances = 0;         ///< quads
    std::uint64_t morphedUploads = 0;    ///< morphed cells uploaded this frame
    std::uint64_t atlasUploads = 0;      ///< atlases uploaded this frame (first use)
    std::uint64_t poolOverflows = 0;     ///< cell uses shown as their previous key-frame: morph pool full
};

/// Camera-facing impostor quads drawn into a context's current framebuffer.
class ImpostorRenderer {
public:
    /// Compiles the quad program in `context`; each atlas gets `morphLayers` layers for the morphed
    /// cells of a frame beside its stored cells (texture memory: stored + morphLayers cells; a
    /// frame needing more shows the previous key-frame for the rest). Throws
    /// std::invalid_argument if `context` is null and std::runtime_error with the log if a shader
    /// fails.
    explicit ImpostorRenderer(std::shared_ptr<GlContext> context, int morphLayers = 256);
    ~ImpostorRenderer();
    ImpostorRenderer(const ImpostorRenderer&) = delete;
    ImpostorRenderer& operator=(const ImpostorRenderer&) = delete;

    /// Draws `instances` seen by `camera` into the context's framebuffer (not cleared), with depth
    /// test and alpha test. Throws std::runtime_error if an atlas needs more layers than the GL
    /// allows.
    void draw(const Camera& camera, std::span<const ImpostorInstance> instances);
    /// Statistics of the last draw().
    const ImpostorRenderStatistics& statistics() const;
    /// Bytes of GPU texture held for impostors (all atlases uploaded so far).
    std::size_t textureBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
