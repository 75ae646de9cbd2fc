#pragma once
// The OpenGL DrawBackend: draws a frame's DrawList of MeshDrawables. Meshes and textures are
// uploaded once (keyed on their shared pointers); items sharing a mesh are drawn instanced; skinned
// items are skinned in the vertex shader from a bone palette in a texture buffer, or on the CPU;
// model matrices are made relative to the eye in double precision so actors 10^7 m from the origin
// render as well as at the origin. Key-pose items (Representation::KeyPose, seed 004) are drawn
// from key-pose caches the renderer keeps per (mesh, KeyPoseSource): rows of skinned vertices
// filled with the renderer's own GPU skinning only when a row does not yet hold the pose an item
// wants there, so a pose kept across frames is skinned once.

#include <memory>

#include "throng/render/RenderStatistics.h"
#include "throng/render/RendererOptions.h"
#include "throng/scenegraph/DrawBackend.h"
#include "throng/scenegraph/Image.h"

namespace throng {

class GlContext;
class KeyPoseSource;

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
    /// times per frame. Key-pose items are drawn instanced per (mesh, source) from the source's cache
    /// rows (`keyPose.row[0]`, or rows 0 and 1 blended when `keyPose.blend` is not 0), after the rows
    /// whose poses changed are skinned with `source->palette(skin, pose)`; their skin palette fields
    /// are ignored. Throws std::logic_error outside beginFrame/endFrame and std::invalid_argument
    /// naming the item if one has no world matrix or a palette shorter than its mesh's joint indices
    /// need, or, for a key-pose item: no source, a mesh without skin, a blend outside [0, 1], a row
    /// or pose outside its source's, a source palette shorter than the mesh needs, or a row another
    /// item of the list wants to hold another pose; nothing of `list` is drawn then, and no cache
    /// changes. Throws std::runtime_error if a cache would exceed the GL's texture buffer size.
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
    /// Frees the key-pose caches of `source` (every mesh). A source is known by its address: call
    /// this before destroying a source this renderer has drawn, or a new source made at the same
    /// address with the same row and pose counts would be drawn from the old one's rows.
    void releaseKeyPoses(const KeyPoseSource& source);
    /// Number of key-pose caches (one per mesh and source) holding GPU rows.
    std::size_t cachedKeyPoseCount() const;
    /// GPU bytes held by the key-pose caches (kKeyPoseVertexBytes per vertex per row).
    std::size_t keyPoseCacheBytes() const;
    /// Bytes one vertex takes in a key-pose cache: the position's float bits and the normal
    /// octahedron-encoded in two 16-bit snorms.
    static constexpr std::size_t kKeyPoseVertexBytes = 16;
    /// The context drawn into.
    GlContext& context() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
