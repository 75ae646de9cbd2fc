#pragma once
// DRAW of a crowd frame, the one backend throng-town, the benchmarks and the tests use: the draw
// list's meshes (GlRenderer: instanced, GPU-skinned), then its impostors (ImpostorBatcher picks
// views and key-frames from what each item records, a shared MorphCache morphs dropped key-frames
// once per frame whatever the crowd, ImpostorRenderer draws the quads), then an optional text
// overlay. Everything it needs is in the draw list: it never looks into the crowd or the scene,
// so it can draw frame N while frame N+1 is being processed. The impostor machinery is built on
// the first impostor item: a scene without impostors never pays for it.

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "throng/render/Caption.h"
#include "throng/render/GpuPassTimer.h"
#include "throng/render/ImpostorBatcher.h"
#include "throng/render/ImpostorRenderer.h"
#include "throng/render/MorphCache.h"
#include "throng/render/RenderStatistics.h"
#include "throng/render/RendererOptions.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawBackend.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Image.h"

namespace throng {

class GlContext;
class GlRenderer;
class GpuMorpher;
class ImageOverlay;
class ScaledFrame;
class TextOverlay;

/// How a CrowdRenderer morphs the impostors' dropped key-frames.
enum class ImpostorMorphing {
    Pool,        ///< the renderer's pool: cells kept on the GPU across frames, a budget of new ones a frame
    FrameCache,  ///< the batcher's MorphCache: every cell of the frame made (or kept on the CPU) and uploaded each frame
};

/// How a CrowdRenderer draws.
struct CrowdRendererOptions {
    RendererOptions meshes;          ///< the mesh renderer's options
    /// The impostor quads and their pool of morphed cells (pool size, morph budget, GL or CPU).
    ImpostorRendererOptions impostors;
    ImpostorMorphing morphing = ImpostorMorphing::Pool;  ///< how dropped key-frames are made
    /// FrameCache only: the morph cache's options (by default 4096 cells kept across frames).
    MorphCacheOptions morph = [] {
        MorphCacheOptions o;
        o.capacity = 4096;
        return o;
    }();
    bool gpuMorph = true;            ///< FrameCache only: morph with the GL and read back (else on the CPU)
    ImpostorViewChoice views;        ///< how impostors pick their views for the eye (seed 003 §4.1)
    /// Waits for the GL after each pass, so each pass's time includes its rasterisation (for
    /// benchmarks: a software GL otherwise rasterises when the frame ends). Slightly slower.
    bool finishPasses = false;
    /// Draws the items of the generic scene (no actor). Off when the host application draws its
    /// own scene and Throng draws the crowd into it (CrowdProp in a VTK renderer).
    bool drawScene = true;
    /// Dynamic resolution: frames are drawn at this fraction of the context's width and height and
    /// scaled up (0 < scale <= 1; 1: full resolution). Not for a host's framebuffer whose depth the
    /// crowd must meet (CrowdProp): the scaled frame's depth stays off screen.
    float renderScale = 1.0f;
};

/// What one frame of a CrowdRenderer cost and drew.
struct CrowdRenderStatistics {
    RenderStatistics meshes;             ///< the mesh passes (scene and actors together)
    ImpostorBatchStatistics impostors;   ///< impostor selection and batching (morphing included)
    MorphCacheStatistics morphs;         ///< FrameCache: the morph cache's work
    std::uint64_t cellsMorphed = 0;      ///< morphed cells made this frame (either way)
    double morphMs = 0;                  ///< time making them (part of impostorBatchMs)
    ImpostorRenderStatistics quads;      ///< the quad pass
    std::uint64_t sceneItems = 0;        ///< items of the generic scene (no actor)
    std::uint64_t skinnedItems = 0;      ///< mesh items drawn with a skin palette
    std::uint64_t keyPoseItems = 0;      ///< items drawn from a key-pose cache (in the actors' mesh pass)
    double sceneMs = 0;                  ///< the generic scene's meshes (a town)
    double meshMs = 0;                   ///< the actors' meshes
    double impostorBatchMs = 0;          ///< impostor selection, batching and morphing
    double impostorDrawMs = 0;           ///< quad pass
    double endFrameMs = 0;               ///< scaling up, overlay, finishing and presenting the frame
    /// Of endFrameMs, the wait in present() for the GPU (or llvmpipe) to finish or swap the frame:
    /// the frame's DRAW less this is the CPU's own work, preparing and submitting.
    double presentMs = 0;
    /// GPU time of each pass (GL timer queries) of the newest frame the GPU has finished: this one
    /// headless, an earlier one in a window (gpuFramesBehind says how many; -1: none finished yet).
    GpuPassTimes gpu;
    std::int64_t gpuFramesBehind = -1;   ///< this frame's number less gpu.frame, or -1
    int renderWidth = 0;                 ///< width the frame was drawn at (below the context's when scaled)
    int renderHeight = 0;                ///< see renderWidth
    // Without finishPasses the GL may rasterise a pass's triangles later, in endFrame.
};

/// The DRAW stage of crowd frames.
class CrowdRenderer final : public DrawBackend {
public:
    /// A renderer drawing into `context`. Throws as GlRenderer does.
    explicit CrowdRenderer(std::shared_ptr<GlContext> context, const CrowdRendererOptions& options = {});
    ~CrowdRenderer() override;
    CrowdRenderer(const CrowdRenderer&) = delete;
    CrowdRenderer& operator=(const CrowdRenderer&) = delete;

    void beginFrame(const Camera& camera) override;
    /// Draws `list` in three passes: the generic scene's meshes, the actors' meshes (key-pose items
    /// included), the impostors.
    void draw(const DrawList& list) override;
    /// Finishes the image (scales a scaled frame up, draws the overlays and captions) unless
    /// finishImage() did, then presents it.
    void endFrame() override;
    /// Finishes the frame's image before endFrame(): scaled up, with its overlays and captions, so
    /// that readFrame() sees what the window will show. Once per frame; endFrame() then presents.
    void finishImage();

    /// Uploads these impostors' stored cells now rather than at their first frame (a steady start).
    void preloadImpostors(std::span<const std::shared_ptr<const ImpostorDrawable>> drawables);
    /// Text drawn over the next frames (lines separated by '\n'; empty: none).
    void setOverlayText(std::string text) { overlayText_ = std::move(text); }
    /// An image drawn over the next frames in the bottom-right corner (empty: none).
    void setOverlayImage(Image image) { overlayImage_ = std::move(image); }
    /// Lines of text shown over the next frames, each centred just above its point of the world as
    /// the frame's camera sees it (points behind the eye are skipped): a speaker's caption.
    void setCaptions(std::vector<Caption> captions) { captions_ = std::move(captions); }
    /// New morphed impostor cells per atlas and frame from the next frame on (-1: no limit; see
    /// ImpostorRendererOptions::morphBudget). Throws std::invalid_argument below -1.
    void setMorphBudget(int budget);
    /// Draws the next frames at `scale` x the context's size, scaled up (CrowdRendererOptions::
    /// renderScale). Throws std::invalid_argument unless 0 < scale <= 1.
    void setRenderScale(float scale);
    /// Statistics of the last frame.
    const CrowdRenderStatistics& statistics() const { return stats_; }
    /// The mesh renderer (viewport, resources, options).
    GlRenderer& meshes() { return *meshes_; }
    /// Bytes of GPU texture the impostors hold (stored cells and pools; 0 before any impostor).
    std::size_t impostorTextureBytes() const;
    /// Reads the framebuffer into an RGBA8 image, top row first (see GlRenderer::readFrame).
    Image readFrame();

private:
    void makeQuads();

    std::shared_ptr<GlContext> context_;
    CrowdRendererOptions options_;
    std::unique_ptr<GlRenderer> meshes_;
    std::unique_ptr<GpuMorpher> gpu_;
    std::unique_ptr<GpuPassTimer> gpuTimer_;
    std::unique_ptr<MorphCache> cache_;
    std::unique_ptr<ImpostorBatcher> batcher_;
    std::unique_ptr<ImpostorRenderer> quads_;
    std::unique_ptr<TextOverlay> overlay_;
    std::unique_ptr<ImageOverlay> imageOverlay_;
    std::unique_ptr<ScaledFrame> scaled_;
    bool scaledFrame_ = false;  // this frame is drawn into scaled_
    bool finished_ = false;     // finishImage() ran this frame
    double finishMs_ = 0.0;     // its time, counted in endFrameMs
    std::string overlayText_;
    Image overlayImage_;
    std::vector<Caption> captions_;
    Camera camera_;
    CrowdRenderStatistics stats_;
    DrawList sceneItems_, actorItems_;  // this frame's mesh items, split by pass (pointers kept)
};

}  // namespace throng
