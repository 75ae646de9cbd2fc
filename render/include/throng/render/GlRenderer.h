#pragma once
// The OpenGL DrawBackend: draws a frame's DrawList of MeshDrawables. Meshes and textures are
// uploaded once (keyed on their shared pointers); items sharing a mesh are drawn instanced; skinned
// items are skinned in the vertex shader from a bone palette in a texture buffer, or on the CPU;
// model matrices are made relative to the eye in double precision so actors 10^7 m from the origin
// render as well as at the origin.

#include <memory>

#include "throng/render/RenderStatistics.h"
#include "throng/render/RendererOptions.h"
#include "throng/scenegraph/DrawBackend.h"
#include "throng/scenegraph/Image.h"

namespace throng {

class GlContext;

/// Draws MeshDrawable items with OpenGL 3.3 core into a GlContext's framebuffer.
class GlRenderer final : public DrawBackend {
public:
    /// A renderer drawing into `context` (shared: GPU resources are freed through it). Compiles the
    /// shaders; throws std::invalid_argument if `context` is null or a size option is negative, and
    /// std::runtime_error with the compiler's log if a shader fails.
    explicit GlRenderer(std::shared_ptr<GlContext> context, const RendererOptions& options = {});
    ~GlRenderer() override;
    GlRenderer(const GlRenderer&) = delete;
    GlRenderer& operator=(const GlRenderer&) = delete;

    /// Starts a frame: binds the target, clears it and takes the camera's matrices (the view is
    /// split into a rotation sent to the GPU and the eye position kept in double).
    void beginFrame(const Camera& camera) override;
    /// Draws the MeshDrawable items of `list` (others are skipped and counted). May be called several
    /// times per frame. Throws std::logic_error outside beginFrame/endFrame and std::invalid_argument
    /// naming the item if one has no world matrix or a palette shorter than its mesh's joint indices
    /// need; nothing of `list` is drawn then.
    void draw(const DrawList& list) override;
    /// Ends the frame: captures it when options().captureFrames, then presents it.
    void endFrame() override;

    /// Replaces the options (a size of 0 keeps the current viewport). Throws std::invalid_argument for
    /// negative sizes.
    void setOptions(const RendererOptions& options);
    /// Current options.
    const RendererOptions& options() const;
    /// Resizes the context's framebuffer (or window) and the viewport. Throws std::invalid_argument
    /// naming the bad value unless both are positive and within the GL limits.
    void setViewportSize(int width, int height);
    /// Viewport width in pixels.
    int width() const;
    /// Viewport height in pixels.
    int height() const;

    /// Statistics of the current (or last finished) frame.
    const RenderStatistics& statistics() const;
    /// Reads the framebuffer now into an RGBA8 image, top row first. For a window call it before
    /// endFrame(); headless, the last frame stays readable after endFrame().
    Image readFrame();
    /// The frame captured by the last endFrame() (empty unless options().captureFrames).
    const Image& lastFrame() const;

    /// Frees the GPU copies of meshes and textures whose CPU data no longer exists.
    void releaseUnusedResources();
    /// Number of meshes with a GPU copy.
    std::size_t cachedMeshCount() const;
    /// Number of textures with a GPU copy.
    std::size_t cachedTextureCount() const;
    /// The context drawn into.
    GlContext& context() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
