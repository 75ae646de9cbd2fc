#include "throng/render/ImpostorRenderer.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <future>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <glad/gl.h>
#include <glm/mat3x3.hpp>

#include "throng/render/GlContext.h"
#include "throng/render/GpuMorpher.h"
#include "throng/render/GpuProxyWarper.h"
#include "throng/render/GridMorph.h"
#include "throng/render/MorphPool.h"
#include "throng/render/ProxyWarp.h"
#include "throng/render/ImpostorDrawable.h"
#include "throng/render/ShaderProgram.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Stopwatch.h"
#include "Shaders.h"
#include "WarpedImpostors.h"

namespace throng {
namespace {

const char* const kVertexShader = R"(#version 330 core
// Per instance: centre relative to the eye, half size, tint, three layers and weights.
layout(location = 0) in vec4 iCentreSize;
layout(location = 1) in vec4 iTint;
layout(location = 2) in vec3 iLayers;
layout(location = 3) in vec3 iWeights;
layout(location = 4) in vec4 iRect;  // the part of the cell drawn: u0, v0, u1, v1 (v from the top)
layout(location = 5) in vec3 iRegionLayers;  // the region maps of the three cells shown
layout(location = 6) in uvec4 iLook;         // the actor's BodyLook
uniform mat4 uViewRotationProjection;  // projection * view rotation (the eye at the origin)
uniform vec3 uRight;
uniform vec3 uUp;
out vec2 vUv;
flat out vec3 vLayers;
flat out vec3 vWeights;
flat out vec4 vTint;
flat out vec3 vRegionLayers;
flat out uvec4 vLook;
void main() {
    vec2 uv = mix(iRect.xy, iRect.zw, vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)));
    vec2 corner = vec2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);  // cells are stored top row first
    vec3 p = iCentreSize.xyz + (uRight * corner.x + uUp * corner.y) * iCentreSize.w;
    gl_Position = uViewRotationProjection * vec4(p, 1.0);
    vUv = uv;
    vLayers = iLayers;
    vWeights = iWeights;
    vTint = iTint;
    vRegionLayers = iRegionLayers;
    vLook = iLook;
}
)";

// The fragment shader: the colour blend of three cells; with body regions (uHasRegions), each
// cell's texel times the actor's colour of the region that texel shows (cells of such atlases are
// baked white per region), blended by the same shares.
std::string fragmentShader() {
    return std::string(R"(#version 330 core
uniform sampler2DArray uCells;  // stored cells, then the pool's morphed ones
uniform sampler2DArray uRegions;  // per cell (key-frame * views + view): its texels' body regions / 255
uniform bool uHasRegions;
in vec2 vUv;
flat in vec3 vLayers;
flat in vec3 vWeights;
flat in vec4 vTint;
flat in vec3 vRegionLayers;
flat in uvec4 vLook;
out vec4 fragColor;
)") + detail::srgbEncodeGlsl() + detail::bodyLookGlsl() + R"(
vec4 cell(float layer) {
    return texture(uCells, vec3(vUv, layer));  // one texture: a software GL samples both sides of a branch
}
vec3 paint(float layer) { return regionPaint(uRegions, vec3(vUv, layer), vLook); }
void main() {
    vec4 c0 = cell(vLayers.x);
    vec4 c = vWeights.x * c0;
    vec3 p = vec3(0.0);
    if (uHasRegions) p += vWeights.x * c0.a * paint(vRegionLayers.x);
    if (vWeights.y > 0.0) {
        vec4 c1 = cell(vLayers.y);
        c += vWeights.y * c1;
        if (uHasRegions) p += vWeights.y * c1.a * paint(vRegionLayers.y);
    }
    if (vWeights.z > 0.0) {
        vec4 c2 = cell(vLayers.z);
        c += vWeights.z * c2;
        if (uHasRegions) p += vWeights.z * c2.a * paint(vRegionLayers.z);
    }
    if (c.a < 0.5) discard;  // alpha test: quads write depth like the meshes they replace
    vec3 rgb = c.rgb / c.a;  // cells are premultiplied
    if (uHasRegions) rgb = wearLook(c, p);
    fragColor = vec4(rgb * vTint.rgb, 1.0);
}
)";
}

struct Instance {
    float centreSize[4];
    float tint[4];
    float layers[3];
    float weights[3];
    float rect[4];
    float regionLayers[3];
    std::uint32_t look[4];
};

// One atlas on the GPU: one array texture, stored cells in layers [0, stored), the pool's morphed
// cells after them (slot s in layer stored + s).
struct GpuAtlas {
    unsigned texture = 0;
    unsigned regions = 0;  // with body regions: an R8 array, one layer per cell (key-frame * views + view)
    int stored = 0, poolLayers = 0, cellSize = 0;
    std::vector<int> storedLayer;  // per (keyframe, view): layer, or -1 when dropped
    std::vector<glm::vec4> viewRect;  // per view: the cell area any stored key-frame covers (u0, v0, u1, v1)
    std::unique_ptr<MorphPool> cells;  // which morphed cells the pool holds
    std::unordered_map<const Image*, int> morphedLayer;  // this frame's images carried by instances
    std::vector<Instance> instances;
    bool warped = false;                        // drawn as its warped proxy (options.warped and a proxy)
    WarpedAtlasGpu warpGpu;                     // then: the proxy and the depth of every layer
    std::vector<WarpedInstance> warpedInstances;
    std::weak_ptr<const ImpostorAtlas> owner;
    const ImpostorAtlas* atlas = nullptr;
    bool used = false;  // wanted by this frame
};

// Per view, the part of the cell any stored key-frame covers (alpha > 0) or any key-frame's bone
// lines or surface proxy reach, widened by three texels for bilinear filtering and morphed
// in-betweens, as texture coordinates; the whole cell when `tight` is false or the view is empty.
// Quads drawn over only this part shade the same pixels: outside it every sample is transparent
// and discarded.
std::vector<glm::vec4> coveredRects(const ImpostorAtlas& atlas, bool tight) {
    const std::uint32_t views = atlas.views().viewCount();
    std::vector<glm::vec4> rects(views, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
    if (!tight) return rects;
    const int size = atlas.cellSize();
    for (std::uint32_t v = 0; v < views; ++v) {
        int x0 = size, y0 = size, x1 = -1, y1 = -1;
        // A view on a dropped ring is covered as the stored cells it is regenerated from are.
        for (int k = 0; k < atlas.keyframeCount(); ++k) {
            if (!atlas.stored(k)) continue;
            const CellSources from = atlas.sources(v, k);
            for (int i = 0; i < from.count; ++i) {
                const Image cell = atlas.cell(from.cells[static_cast<std::size_t>(i)].view, k);
                for (int y = 0; y < size; ++y)
                    for (int x = 0; x < size; ++x)
                        if (cell.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)) * 4 + 3] > 0)
                            x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
            }
        }
        if (x1 < 0) continue;
        // Dropped cells keep only their bones' lines: their ends count too, so an in-between
        // reaching beyond every stored pose is still covered.
        const auto include = [&](float x, float y) {
            x0 = std::min(x0, static_cast<int>(std::floor(x))), y0 = std::min(y0, static_cast<int>(std::floor(y)));
            x1 = std::max(x1, static_cast<int>(std::floor(x))), y1 = std::max(y1, static_cast<int>(std::floor(y)));
        };
        for (int k = 0; k < atlas.keyframeCount(); ++k)
            for (const FeatureLine& l : atlas.lines(v, k)) include(l.p.x, l.p.y), include(l.q.x, l.q.y);
        // Cells warped through the surface proxy show the proxy's outline at the dropped key-frame.
        if (atlas.proxy())
            for (int k = 0; k < atlas.keyframeCount(); ++k)
                for (const glm::vec3& e : atlas.proxy()->project(k, atlas.views().direction(v))) include(e.x, e.y);
        const int margin = 3;
        const float s = static_cast<float>(size);
        rects[v] = glm::vec4(static_cast<float>(std::max(x0 - margin, 0)) / s, static_cast<float>(std::max(y0 - margin, 0)) / s,
                             static_cast<float>(std::min(x1 + 1 + margin, size)) / s, static_cast<float>(std::min(y1 + 1 + margin, size)) / s);
    }
    return rects;
}

void setArrayParameters(const GladGLContext& gl) {
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);  // no mipmaps: complete with level 0
}

}  // namespace

// What making one dropped cell on the CPU needs (copies: the atlas may go meanwhile).
struct CpuCell {
    // Through the surface proxy: the stored cells around it (ImpostorAtlas::sources), their eye
    // directions, key-frames and shares.
    std::shared_ptr<const ProxyMesh> proxy;  // the atlas's surface proxy, if it is to be used
    std::array<Image, 4> images;
    std::array<ProxySource, 4> sources{};
    int sourceCount = 0;
    // Along the feature lines: the two stored cells it lies between (images 0 and 1), their
    // lines, the target's, and the fraction between.
    DroppedCellLines lines;
    glm::vec3 toEye{0.0f, 0.0f, 1.0f};       // the view's direction
    int keyframe = 0;                        // the dropped cell's key-frame
};

// The CPU job for cell (`view`, `keyframe`) of `atlas`: the proxy's sources when `proxy` is given,
// else the feature lines' two cells.
CpuCell cpuCellJob(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe, std::shared_ptr<const ProxyMesh> proxy,
                   const MorphCacheOptions& morph) {
    CpuCell job;
    job.toEye = atlas.views().direction(view);
    job.keyframe = keyframe;
    if (proxy) {
        const CellSources from = atlas.sources(view, keyframe);
        for (int i = 0; i < from.count; ++i) {
            const CellSource& c = from.cells[static_cast<std::size_t>(i)];
            job.images[static_cast<std::size_t>(i)] = atlas.cell(c.view, c.keyframe);
            job.sources[static_cast<std::size_t>(i)] = {nullptr, atlas.views().direction(c.view), c.keyframe, c.weight};
        }
        job.sourceCount = from.count;
        job.proxy = std::move(proxy);
        return job;
    }
    job.lines = droppedCellLines(atlas, view, keyframe, morph);
    job.images[0] = atlas.cell(job.lines.fromView, job.lines.before);
    job.images[1] = atlas.cell(job.lines.toView, job.lines.after);
    return job;
}

// A dropped cell made on the CPU: warped through the surface proxy when there is one, otherwise
// morphed along the feature lines (on the warp grid, or per pixel).
Image makeCpuCell(CpuCell& c, const ImpostorRendererOptions& options) {
    if (c.proxy) {
        ProxyWarpOptions warp;
        warp.opaqueInside = true;  // as measured best (throng-impostor-quality)
        for (int i = 0; i < c.sourceCount; ++i) c.sources[static_cast<std::size_t>(i)].image = &c.images[static_cast<std::size_t>(i)];
        return warpProxy(*c.proxy, std::span<const ProxySource>(c.sources.data(), static_cast<std::size_t>(c.sourceCount)), c.toEye,
                         c.keyframe, warp);
    }
    if (options.gridStep > 1)
        return morphImagesOnGrid(c.images[0], c.lines.from, c.images[1], c.lines.to, c.lines.target, c.lines.t, options.morph.parameters,
                                 options.gridStep);
    return morphImages(c.images[0], c.lines.from, c.images[1], c.lines.to, c.lines.target, c.lines.t, options.morph.parameters,
                       options.morph.threads);
}

Image makeDroppedCell(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe, const ImpostorRendererOptions& options) {
    if (view >= atlas.views().viewCount() || keyframe < 0 || keyframe >= atlas.keyframeCount() || atlas.cellStored(view, keyframe))
        throw std::invalid_argument("makeDroppedCell: view " + std::to_string(view) + " key-frame " + std::to_string(keyframe) +
                                    " of '" + atlas.templateName() + "' is not a dropped cell");
    CpuCell job = cpuCellJob(atlas, view, keyframe, options.warp == CellWarp::SurfaceProxy ? atlas.proxy() : nullptr, options.morph);
    return makeCpuCell(job, options);
}

// A cell made on the background thread, and where it goes.
struct BackgroundCell {
    const ImpostorAtlas* atlas = nullptr;
    unsigned texture = 0;  // the texture it was meant for (an atlas uploaded again gets another)
    int layer = 0;
    int slot = 0;
    std::uint32_t view = 0;  // the cell's view (its key-frame is job.keyframe)
    CpuCell job;
    Image result;
};

struct ImpostorRenderer::Impl {
    std::shared_ptr<GlContext> context;  // first member: destroyed last
    ImpostorRendererOptions options;
    std::vector<BackgroundCell> background;  // cells of the last frame, being made by `worker`
    std::future<double> worker;              // returns its time (ms)
    std::unique_ptr<ShaderProgram> program;
    std::unique_ptr<GpuMorpher> morpher;  // made on the first GL morph
    std::unique_ptr<GpuProxyWarper> proxyWarper;  // made on the first GL warp through a surface proxy
    std::unique_ptr<WarpedImpostorPass> warpedPass;  // made on the first atlas drawn warped
    unsigned vao = 0, buffer = 0;
    std::unordered_map<const ImpostorAtlas*, GpuAtlas> atlases;
    ImpostorRenderStatistics stats;
    int maxLayers = 256;

    GpuAtlas& upload(const ImpostorDrawable& d) {
        const ImpostorAtlas& atlas = d.atlas();
        auto it = atlases.find(&atlas);
        if (it != atlases.end() && !it->second.owner.expired()) return it->second;
        const GladGLContext& gl = context->gl();
        GpuAtlas g;
        g.owner = d.atlasPtr();
        g.atlas = &atlas;
        g.cellSize = atlas.cellSize();
        const std::uint32_t views = atlas.views().viewCount();
        g.storedLayer.assign(static_cast<std::size_t>(atlas.keyframeCount()) * views, -1);
        for (int k = 0; k < atlas.keyframeCount(); ++k)
            for (std::uint32_t v = 0; v < views; ++v)
                if (atlas.cellStored(v, k)) g.storedLayer[static_cast<std::size_t>(k) * views + v] = g.stored++;
        g.poolLayers = options.poolSlots;
        if (g.stored + g.poolLayers > maxLayers)
            throw std::runtime_error("ImpostorRenderer: atlas '" + atlas.templateName() + "' needs " +
                                     std::to_string(g.stored + g.poolLayers) + " layers, the GL allows " + std::to_string(maxLayers));
        g.cells = std::make_unique<MorphPool>(options.poolSlots, atlas.keyframeCount(), views);
        const int s = atlas.cellSize();
        gl.GenTextures(1, &g.texture);
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.texture);
        gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, s, s, std::max(g.stored + g.poolLayers, 1), 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        setArrayParameters(gl);
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        g.viewRect = coveredRects(atlas, options.tightQuads);
        for (int k = 0; k < atlas.keyframeCount(); ++k)
            for (std::uint32_t v = 0; v < views; ++v)
                if (atlas.cellStored(v, k)) {
                    const Image cell = atlas.cell(v, k);
                    gl.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, g.storedLayer[static_cast<std::size_t>(k) * views + v], s, s,
                                     1, GL_RGBA, GL_UNSIGNED_BYTE, cell.rgba.data());
                }
        if (atlas.hasRegions()) {
            // Every cell's regions, stored or dropped: regenerated cells read their own.
            gl.GenTextures(1, &g.regions);
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.regions);
            gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R8, s, s, atlas.keyframeCount() * static_cast<int>(views), 0, GL_RED, GL_UNSIGNED_BYTE, nullptr);
            setArrayParameters(gl);
            gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // region numbers do not blend
            gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            for (int k = 0; k < atlas.keyframeCount(); ++k)
                for (std::uint32_t v = 0; v < views; ++v)
                    gl.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, k * static_cast<int>(views) + static_cast<int>(v), s, s, 1, GL_RED,
                                     GL_UNSIGNED_BYTE, atlas.regions(v, k).data());
        }
        if (options.warped && atlas.proxy()) {
            // The proxy on the GPU and the depth of every stored cell, for drawing it warped.
            if (!warpedPass) warpedPass = std::make_unique<WarpedImpostorPass>(*context);
            g.warped = true;
            g.warpGpu = warpedPass->upload(atlas, g.stored + g.poolLayers);
            for (int k = 0; k < atlas.keyframeCount(); ++k)
                for (std::uint32_t v = 0; v < views; ++v)
                    if (atlas.cellStored(v, k)) warpedPass->depthInto(atlas, g.warpGpu, g.storedLayer[static_cast<std::size_t>(k) * views + v], v, k);
        }
        ++stats.atlasUploads;
        if (it != atlases.end()) {
            forget(it->second);
            atlases.erase(it);
        }
        return atlases.emplace(&atlas, std::move(g)).first->second;
    }

    // Frees an atlas's GL objects.
    void forget(GpuAtlas& g) {
        context->gl().DeleteTextures(1, &g.texture);
        if (g.regions) context->gl().DeleteTextures(1, &g.regions);
        if (g.warped) warpedPass->release(g.warpGpu);
    }

    // The stored cell shown for a cell that is not ready: the stored cell of the largest share
    // among those it is regenerated from (the nearest key-frame and ring; the first on a tie).
    static CellSource fallbackCell(const ImpostorAtlas& atlas, int keyframe, std::uint32_t view) {
        const CellSources from = atlas.sources(view, keyframe);
        const CellSource* best = &from.cells[0];
        for (int i = 1; i < from.count; ++i)
            if (from.cells[static_cast<std::size_t>(i)].weight > best->weight) best = &from.cells[static_cast<std::size_t>(i)];
        return *best;
    }
    // Its layer.
    static int layerOf(const GpuAtlas& g, const ImpostorAtlas& atlas, const CellSource& c) {
        return std::max(g.storedLayer[static_cast<std::size_t>(c.keyframe) * atlas.views().viewCount() + c.view], 0);
    }
    // A pool layer now holds cell (view, keyframe): its depth too, when the atlas is drawn warped.
    void filled(GpuAtlas& g, int layer, std::uint32_t view, int keyframe) {
        if (g.warped) warpedPass->depthInto(*g.atlas, g.warpGpu, layer, view, keyframe);
    }

    // Makes this frame's chosen cells of `g` in its pool: on the GL straight into the layer, or on
    // the CPU and uploaded.
    void morphCells(GpuAtlas& g, std::span<const MorphFill> fills) {
        const ImpostorAtlas& atlas = *g.atlas;
        const GladGLContext& gl = context->gl();
        const std::uint32_t views = atlas.views().viewCount();
        for (const MorphFill& f : fills) {
            if (options.source == MorphSource::Cpu) {
                CpuCell job = cpuCellJob(atlas, f.view, f.keyframe, options.warp == CellWarp::SurfaceProxy ? atlas.proxy() : nullptr,
                                         options.morph);
                if (options.backgroundMorph) {
                    g.cells->setPending(f.slot);
                    background.push_back({&atlas, g.texture, g.stored + f.slot, f.slot, f.view, std::move(job), {}});
                    continue;
                }
                const Image cell = makeCpuCell(job, options);
                gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.texture);
                gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
                gl.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, g.stored + f.slot, g.cellSize, g.cellSize, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                                 cell.rgba.data());
                ++stats.morphedUploads;
                filled(g, g.stored + f.slot, f.view, f.keyframe);
            } else if (options.warp == CellWarp::SurfaceProxy && atlas.proxy()) {
                // Through the figure's surface, as the CPU path does (warpProxy), in the GL.
                if (!proxyWarper) proxyWarper = std::make_unique<GpuProxyWarper>(context);
                const CellSources from = atlas.sources(f.view, f.keyframe);
                std::array<GpuProxyWarper::LayerSource, 4> sources{};
                for (int i = 0; i < from.count; ++i) {
                    const CellSource& c = from.cells[static_cast<std::size_t>(i)];
                    sources[static_cast<std::size_t>(i)] = {g.storedLayer[static_cast<std::size_t>(c.keyframe) * views + c.view],
                                                            atlas.views().direction(c.view), c.keyframe, c.weight};
                }
                ProxyWarpOptions warp;
                warp.opaqueInside = true;  // as the CPU path
                proxyWarper->warpInto(*atlas.proxy(), g.texture,
                                      std::span<const GpuProxyWarper::LayerSource>(sources.data(), static_cast<std::size_t>(from.count)),
                                      atlas.views().direction(f.view), f.keyframe, g.texture, g.stored + f.slot, warp);
                filled(g, g.stored + f.slot, f.view, f.keyframe);
            } else {
                const DroppedCellLines c = droppedCellLines(atlas, f.view, f.keyframe, options.morph);
                if (!morpher) morpher = std::make_unique<GpuMorpher>(context);
                morpher->morphInto(g.texture, g.storedLayer[static_cast<std::size_t>(c.before) * views + c.fromView],
                                   g.storedLayer[static_cast<std::size_t>(c.after) * views + c.toView], g.texture, g.stored + f.slot, g.cellSize,
                                   c.from, c.to, c.target, c.t, options.morph.parameters);
                filled(g, g.stored + f.slot, f.view, f.keyframe);
            }
        }
    }
};

// Morphs every background cell (on the worker thread); returns the time taken.
double morphBackground(std::vector<BackgroundCell>& cells, const ImpostorRendererOptions& options) {
    Stopwatch watch;
    for (BackgroundCell& c : cells) c.result = makeCpuCell(c.job, options);
    return watch.elapsedMs();
}

ImpostorRenderer::ImpostorRenderer(std::shared_ptr<GlContext> context, const ImpostorRendererOptions& options) {
    if (!context) throw std::invalid_argument("ImpostorRenderer: argument 'context' is null");
    if (options.poolSlots < 0) throw std::invalid_argument("ImpostorRenderer: poolSlots must be >= 0, not " + std::to_string(options.poolSlots));
    if (options.gridStep < 1) throw std::invalid_argument("ImpostorRenderer: gridStep must be >= 1, not " + std::to_string(options.gridStep));
    impl_ = std::make_unique<Impl>();
    Impl& r = *impl_;
    r.options = options;
    r.context = std::move(context);
    r.context->makeCurrent();
    const GladGLContext& gl = r.context->gl();
    r.program = std::make_unique<ShaderProgram>(*r.context, "ImpostorRenderer shader", kVertexShader, fragmentShader());
    gl.GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &r.maxLayers);
    gl.GenVertexArrays(1, &r.vao);
    gl.GenBuffers(1, &r.buffer);
    gl.BindVertexArray(r.vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r.buffer);
    const auto stride = static_cast<GLsizei>(sizeof(Instance));
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Instance, centreSize)));
    gl.EnableVertexAttribArray(1);
    gl.VertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Instance, tint)));
    gl.EnableVertexAttribArray(2);
    gl.VertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Instance, layers)));
    gl.EnableVertexAttribArray(3);
    gl.VertexAttribPointer(3, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Instance, weights)));
    gl.EnableVertexAttribArray(4);
    gl.VertexAttribPointer(4, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Instance, rect)));
    gl.EnableVertexAttribArray(5);
    gl.VertexAttribPointer(5, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Instance, regionLayers)));
    gl.EnableVertexAttribArray(6);
    gl.VertexAttribIPointer(6, 4, GL_UNSIGNED_INT, stride, reinterpret_cast<void*>(offsetof(Instance, look)));
    for (GLuint a = 0; a < 7; ++a) gl.VertexAttribDivisor(a, 1);
    gl.BindVertexArray(0);
    gl.UseProgram(r.program->id());
    gl.Uniform1i(r.program->uniformLocation("uCells"), 0);
    gl.Uniform1i(r.program->uniformLocation("uRegions"), 1);
    gl.UseProgram(0);
}

ImpostorRenderer::~ImpostorRenderer() {
    Impl& r = *impl_;
    try {
        r.context->makeCurrent();
    } catch (...) {
        return;
    }
    if (r.worker.valid()) r.worker.wait();
    const GladGLContext& gl = r.context->gl();
    for (auto& [atlas, g] : r.atlases) r.forget(g);
    r.warpedPass.reset();
    gl.DeleteBuffers(1, &r.buffer);
    gl.DeleteVertexArrays(1, &r.vao);
    r.morpher.reset();
    r.proxyWarper.reset();
    r.program.reset();
}

const ImpostorRenderStatistics& ImpostorRenderer::statistics() const { return impl_->stats; }

const ImpostorRendererOptions& ImpostorRenderer::options() const { return impl_->options; }

void ImpostorRenderer::setMorphBudget(int budget) {
    if (budget < -1) throw std::invalid_argument("ImpostorRenderer: morph budget must be >= -1, not " + std::to_string(budget));
    impl_->options.morphBudget = budget;
}

std::size_t ImpostorRenderer::textureBytes() const {
    std::size_t bytes = 0;
    for (const auto& entry : impl_->atlases) {
        const GpuAtlas& g = entry.second;
        const std::size_t layerBytes = static_cast<std::size_t>(g.cellSize) * static_cast<std::size_t>(g.cellSize) * 4;
        bytes += static_cast<std::size_t>(g.stored + g.poolLayers) * layerBytes;
        if (g.regions) bytes += g.atlas->regionBytes();
        if (g.warped) bytes += static_cast<std::size_t>(g.warpGpu.layers) * layerBytes + g.warpGpu.bytes;  // depth layers, proxy
    }
    return bytes;
}

void ImpostorRenderer::preload(const ImpostorDrawable& drawable) {
    impl_->context->makeCurrent();
    impl_->upload(drawable);
}

void ImpostorRenderer::draw(const Camera& camera, std::span<const ImpostorInstance> instances) {
    Impl& r = *impl_;
    r.stats = {};
    r.context->makeCurrent();
    const GladGLContext& gl = r.context->gl();
    // The cells the background thread made since the last frame: uploaded, then shown.
    if (r.worker.valid()) {
        Stopwatch wait;
        r.stats.backgroundMorphMs = r.worker.get();
        r.stats.backgroundWaitMs = wait.elapsedMs();
        for (BackgroundCell& c : r.background) {
            auto it = r.atlases.find(c.atlas);
            if (it == r.atlases.end() || it->second.texture != c.texture) continue;  // its atlas went
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, c.texture);
            gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
            gl.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, c.layer, c.result.width, c.result.height, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                             c.result.rgba.data());
            r.filled(it->second, c.layer, c.view, c.job.keyframe);
            it->second.cells->setReady(c.slot);
            ++r.stats.morphedUploads;
        }
        r.background.clear();
    }
    for (auto& [atlas, g] : r.atlases) {
        g.instances.clear();
        g.warpedInstances.clear();
        g.morphedLayer.clear();
        g.cells->beginFrame();
        g.used = false;
    }
    // Pass 1: which morphed cells the frame wants, per atlas.
    for (const ImpostorInstance& inst : instances) {
        if (!inst.drawable) continue;
        GpuAtlas& g = r.upload(*inst.drawable);
        g.used = true;
        const ImpostorAtlas& atlas = inst.drawable->atlas();
        for (std::size_t i = 0; i < 3; ++i)
            if (inst.weights[i] > 0.0f && !inst.morphed[i] && !atlas.cellStored(inst.views[i], inst.keyframe))
                g.cells->want(inst.keyframe, inst.views[i]);
    }
    // The most wanted new cells, within the budget, made now.
    Stopwatch watch;
    for (auto& [atlas, g] : r.atlases) {
        if (!g.used) continue;
        const std::span<const MorphFill> fills = g.cells->resolve(r.options.morphBudget);
        r.morphCells(g, fills);
        const MorphPoolStatistics& p = g.cells->statistics();
        r.stats.cellsWanted += p.wanted;
        r.stats.cellsResident += p.resident;
        r.stats.cellsMorphed += p.made;
        r.stats.cellsDeferred += p.deferred;
    }
    if (!r.background.empty())
        r.worker = std::async(std::launch::async, [&r] { return morphBackground(r.background, r.options); });
    r.stats.morphMs = watch.elapsedMs();
    // Pass 2: the quads, each cell's layer resolved.
    for (const ImpostorInstance& inst : instances) {
        if (!inst.drawable) continue;
        const ImpostorAtlas& atlas = inst.drawable->atlas();
        GpuAtlas& g = r.atlases.find(&atlas)->second;
        const std::uint32_t views = atlas.views().viewCount();
        Instance out{};
        const glm::dvec3 rel = inst.centre - camera.eye();
        out.centreSize[0] = static_cast<float>(rel.x);
        out.centreSize[1] = static_cast<float>(rel.y);
        out.centreSize[2] = static_cast<float>(rel.z);
        out.centreSize[3] = inst.halfSize;
        for (int c = 0; c < 4; ++c) out.tint[c] = inst.tint[c];
        for (std::size_t c = 0; c < 4; ++c) out.look[c] = inst.look.rgba[c];
        glm::vec4 rect(1.0f, 1.0f, 0.0f, 0.0f);  // the union of the blended views' rectangles
        std::array<float, 3> sourceViews{}, sourceKeyframes{};
        for (std::size_t i = 0; i < 3; ++i) {
            if (inst.weights[i] > 0.0f && inst.views[i] < views) {
                const glm::vec4& v = g.viewRect[inst.views[i]];
                rect = glm::vec4(std::min(rect.x, v.x), std::min(rect.y, v.y), std::max(rect.z, v.z), std::max(rect.w, v.w));
            }
            out.weights[i] = inst.weights[i];
            int layer = 0;
            CellSource shown{inst.views[i], inst.keyframe, inst.weights[i]};  // the cell the layer holds
            if (inst.weights[i] <= 0.0f) {
                layer = 0;
            } else if (atlas.cellStored(inst.views[i], inst.keyframe)) {
                layer = std::max(g.storedLayer[static_cast<std::size_t>(inst.keyframe) * views + inst.views[i]], 0);
            } else if (inst.morphed[i]) {
                // An image the batcher's MorphCache made: uploaded into a pool layer for this frame.
                auto found = g.morphedLayer.find(inst.morphed[i]);
                if (found == g.morphedLayer.end() && static_cast<int>(g.morphedLayer.size()) >= g.poolLayers) {
                    ++r.stats.poolOverflows;
                    shown = Impl::fallbackCell(atlas, inst.keyframe, inst.views[i]);
                    layer = Impl::layerOf(g, atlas, shown);
                } else {
                    if (found == g.morphedLayer.end()) {
                        if (g.morphedLayer.empty()) g.cells->clear();  // the pool's layers hold this frame's images
                        found = g.morphedLayer.emplace(inst.morphed[i], static_cast<int>(g.morphedLayer.size())).first;
                        gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.texture);
                        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
                        gl.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, g.stored + found->second, atlas.cellSize(), atlas.cellSize(), 1, GL_RGBA,
                                         GL_UNSIGNED_BYTE, inst.morphed[i]->rgba.data());
                        ++r.stats.morphedUploads;
                        r.filled(g, g.stored + found->second, inst.views[i], inst.keyframe);
                    }
                    layer = g.stored + found->second;
                }
            } else if (const int slot = g.cells->slotOf(inst.keyframe, inst.views[i]); slot >= 0) {
                layer = g.stored + slot;
            } else {
                ++r.stats.poolOverflows;
                shown = Impl::fallbackCell(atlas, inst.keyframe, inst.views[i]);
                layer = Impl::layerOf(g, atlas, shown);
            }
            out.layers[i] = static_cast<float>(layer);
            sourceViews[i] = static_cast<float>(shown.view);
            sourceKeyframes[i] = static_cast<float>(shown.keyframe);
            out.regionLayers[i] = static_cast<float>(static_cast<std::uint32_t>(shown.keyframe) * views + shown.view);
        }
        if (g.warped) {
            WarpedInstance w{};
            const glm::dvec3 origin = inst.origin - camera.eye();
            w.originPhase[0] = static_cast<float>(origin.x), w.originPhase[1] = static_cast<float>(origin.y);
            w.originPhase[2] = static_cast<float>(origin.z), w.originPhase[3] = inst.phase;
            for (int c = 0; c < 3; ++c) {
                w.axisX[c] = inst.axes[0][c], w.axisY[c] = inst.axes[1][c], w.axisZ[c] = inst.axes[2][c];
                w.layers[c] = out.layers[c];
                w.keyframes[c] = sourceKeyframes[static_cast<std::size_t>(c)], w.weights[c] = out.weights[c];
            }
            WarpedImpostorPass::setViews(atlas, w, sourceViews.data());
            for (int c = 0; c < 4; ++c) w.tint[c] = out.tint[c], w.look[c] = out.look[c];
            for (int c = 0; c < 3; ++c) w.regionLayers[c] = out.regionLayers[c];
            g.warpedInstances.push_back(w);
            continue;
        }
        if (rect.x >= rect.z) rect = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
        for (int c = 0; c < 4; ++c) out.rect[c] = rect[c];
        g.instances.push_back(out);
    }
    // The eye at the origin: only the view's rotation goes to the GPU (float precision far away).
    glm::dmat4 rotation = camera.view();
    rotation[3] = glm::dvec4(0, 0, 0, 1);
    const glm::mat4 vrp(camera.projection() * rotation);
    const glm::dmat3 inverse = glm::transpose(glm::dmat3(camera.view()));
    const glm::vec3 right(inverse[0]), up(inverse[1]);
    const GlContext::DrawTarget target = r.context->drawTarget();
    gl.BindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
    gl.Viewport(target.x, target.y, target.width, target.height);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_BLEND);
    gl.UseProgram(r.program->id());
    gl.UniformMatrix4fv(r.program->uniformLocation("uViewRotationProjection"), 1, GL_FALSE, &vrp[0][0]);
    gl.Uniform3f(r.program->uniformLocation("uRight"), right.x, right.y, right.z);
    gl.Uniform3f(r.program->uniformLocation("uUp"), up.x, up.y, up.z);
    gl.BindVertexArray(r.vao);
    const GLint hasRegions = r.program->uniformLocation("uHasRegions");
    for (auto& [atlas, g] : r.atlases) {
        if (g.instances.empty()) continue;
        gl.Uniform1i(hasRegions, g.regions != 0 && r.options.bodyLooks);
        gl.ActiveTexture(GL_TEXTURE1);
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.regions);
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.texture);
        gl.BindBuffer(GL_ARRAY_BUFFER, r.buffer);
        gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(g.instances.size() * sizeof(Instance)), g.instances.data(),
                      GL_STREAM_DRAW);
        gl.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(g.instances.size()));
        ++r.stats.drawCalls;
        r.stats.instances += g.instances.size();
    }
    // Atlases drawn warped: the proxy per impostor, one instanced call each.
    for (auto& [atlas, g] : r.atlases) {
        if (g.warpedInstances.empty()) continue;
        r.warpedPass->draw(*g.atlas, g.warpGpu, g.texture, r.options.bodyLooks ? g.regions : 0u, g.warpedInstances, vrp);
        ++r.stats.drawCalls;
        r.stats.instances += g.warpedInstances.size();
    }
    gl.BindVertexArray(0);
    gl.UseProgram(0);
}

}  // namespace throng
