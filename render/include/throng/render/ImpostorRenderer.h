#pragma once
// Draws ImpostorBatcher's instances with OpenGL: camera-facing quads, one instanced call per atlas,
// each blending its three view cells by their weights in the fragment shader. An atlas lives in one
// 2-D array texture: its stored cells (a layer each, uploaded once), then a few layers for morphed
// cells, the pool (MorphPool): a cell is morphed once into a pool layer and stays there across
// frames while it is wanted, at most `morphBudget` new cells a frame, the most wanted first; an
// impostor whose cell is not ready shows its nearest stored key-frame. Cells are morphed by the GL
// into the layer (no read-back) or on the CPU and uploaded.
// Draw after GlRenderer::draw() and before endFrame(): quads are depth-tested against the meshes.

#include <cstdint>
#include <memory>
#include <span>

#include "throng/render/ImpostorBatcher.h"
#include "throng/render/MorphCache.h"

namespace throng {

class Camera;
class GlContext;

/// Where the pool's new cells are morphed.
enum class MorphSource {
    Gpu,  ///< by the GL, into the pool layer (GpuMorpher::morphInto): no read-back, no upload
    Cpu,  ///< on the CPU (morphImages), then uploaded into the pool layer
};

/// How a dropped key-frame's cell is made from its stored neighbours (on the CPU or the GL).
enum class CellWarp {
    FeatureLines,  ///< Beier-Neely field morphing along the bones' lines (MorphCache's features)
    /// Through the figure's surface (warpProxy) when the atlas carries a proxy (ImpostorSet bakes
    /// one), else along the feature lines: limbs stay whole where lines would bend the background.
    SurfaceProxy,
};

/// How an ImpostorRenderer keeps and makes morphed cells.
struct ImpostorRendererOptions {
    /// Pool layers per atlas (texture memory: stored cells + these). Instances that carry their
    /// own morphed images (a batcher with a MorphCache) use them as per-frame layers instead.
    int poolSlots = 48;
    // The defaults are the cheapest path measured on a software GL (llvmpipe, bench_impostor_frame):
    // the CPU on a warp grid, on another thread, two new cells per atlas and frame. On a hardware
    // GL, MorphSource::Gpu morphs without taking CPU time.
    int morphBudget = 2;                    ///< new cells morphed per atlas and frame (negative: no limit)
    MorphSource source = MorphSource::Cpu;  ///< where new cells are morphed
    /// Cpu: the warp evaluated every gridStep pixels and interpolated between (morphImagesOnGrid;
    /// 1: at every pixel, as the GL does).
    int gridStep = 4;
    /// How cells are made, on either side (the GL warps through the proxy with GpuProxyWarper).
    CellWarp warp = CellWarp::SurfaceProxy;
    /// Cpu: new cells are morphed on another thread while the frame goes on, and shown from the
    /// next frame (until then, the nearest stored key-frame). Deterministic: the next draw() waits
    /// for them.
    bool backgroundMorph = true;
    MorphCacheOptions morph;                ///< features, line targets, Beier-Neely parameters, CPU threads
    /// Quads cover only the part of the cell the blended views ever cover (the same pixels drawn:
    /// the rest is transparent and discarded), not the whole cell.
    bool tightQuads = true;
    /// Impostors whose atlas has a surface proxy are drawn as that proxy warped to the eye and the
    /// actor's clip time (ImpostorViewChoice::warped; CrowdRenderer sets this from it).
    bool warped = false;
    /// Atlases with body regions are drawn wearing each actor's look (BodyLook); off, their cells
    /// as baked (white per region) and the pass without the region lookups: what the looks cost.
    bool bodyLooks = true;
};

/// What ImpostorRenderer did in the last draw().
struct ImpostorRenderStatistics {
    std::uint64_t drawCalls = 0;         ///< instanced calls
    std::uint64_t instances = 0;         ///< quads
    std::uint64_t morphedUploads = 0;    ///< morphed images uploaded this frame (CPU-made cells)
    std::uint64_t atlasUploads = 0;      ///< atlases uploaded this frame (first use)
    std::uint64_t poolOverflows = 0;     ///< cell uses shown as their nearest stored key-frame: not ready
    std::uint64_t cellsWanted = 0;       ///< distinct morphed cells the frame wants (pool path)
    std::uint64_t cellsResident = 0;     ///< of those, made in an earlier frame
    std::uint64_t cellsMorphed = 0;      ///< made this frame
    std::uint64_t cellsDeferred = 0;     ///< left to later frames by the budget or the pool size
    double morphMs = 0;                  ///< time issuing (GL) or doing (CPU) this frame's morphs on the drawing thread
    double backgroundMorphMs = 0;        ///< backgroundMorph: the other thread's time for the cells made ready this frame
    double backgroundWaitMs = 0;         ///< backgroundMorph: time this draw() waited for that thread
};

/// Dropped cell (`view`, `keyframe`) of `atlas` made on the CPU exactly as an ImpostorRenderer with
/// `options` makes it (MorphSource::Cpu; the GL's GpuProxyWarper agrees with it): for measuring
/// what the run time shows against truly rendered cells. Throws std::invalid_argument if the cell
/// is out of range or stored.
Image makeDroppedCell(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe, const ImpostorRendererOptions& options);

/// Camera-facing impostor quads drawn into a context's current framebuffer.
class ImpostorRenderer {
public:
    /// Compiles the quad program in `context`. Throws std::invalid_argument if `context` is null
    /// or an option is out of range, and std::runtime_error with the log if a shader fails.
    explicit ImpostorRenderer(std::shared_ptr<GlContext> context, const ImpostorRendererOptions& options = {});
    ~ImpostorRenderer();
    ImpostorRenderer(const ImpostorRenderer&) = delete;
    ImpostorRenderer& operator=(const ImpostorRenderer&) = delete;

    /// Draws `instances` seen by `camera` into the context's framebuffer (not cleared), with depth
    /// test and alpha test. Throws std::runtime_error if an atlas needs more layers than the GL
    /// allows.
    void draw(const Camera& camera, std::span<const ImpostorInstance> instances);
    /// Uploads `drawable`'s stored cells now rather than at its first draw (a steady first frame).
    void preload(const ImpostorDrawable& drawable);
    /// Options.
    const ImpostorRendererOptions& options() const;
    /// Changes the morph budget from the next draw() (a frame-budget allocator trades it for time).
    /// Throws std::invalid_argument if it is below -1 (-1: no limit).
    void setMorphBudget(int budget);
    /// Statistics of the last draw().
    const ImpostorRenderStatistics& statistics() const;
    /// Bytes of GPU texture held for impostors (all atlases uploaded so far: stored cells and pools).
    /// Drawn warped, their depth layers and proxies too.
    std::size_t textureBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
