#include "throng/render/GpuProxyWarper.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <glad/gl.h>

#include "GlslSampling.h"
#include "TextureLayerFit.h"
#include "throng/render/GlContext.h"
#include "throng/render/ShaderProgram.h"

namespace throng {
namespace {

constexpr int kSources = static_cast<int>(GpuProxyWarper::kMaxSources);
constexpr int kFloatsPerVertex = 3 * (1 + kSources);  // the target's projection, then each source's
constexpr float kEmptyDepth = -1e30f;                  // a source's depth where no surface covers it

// Cell pixels (x right, y rows down) onto the viewport so that GL row j is image row j: what is
// read back, or sampled with texelFetch, is in the image's own row order. Depth: larger z (nearer
// the eye) passes GL_LESS.
const char* const kProjection = R"(
uniform float uSize;
uniform float uDepthRange;
vec4 cellToClip(vec3 p) {
    return vec4(p.x / uSize * 2.0 - 1.0, p.y / uSize * 2.0 - 1.0, clamp(-p.z / uDepthRange, -1.0, 1.0), 1.0);
}
)";

// The depth pass: the proxy at one source's pose; each pixel keeps the nearest surface's depth.
const char* const kDepthVertex = R"(
layout(location = 0) in vec3 aPosition;
noperspective out float vDepth;
void main() {
    vDepth = aPosition.z;
    gl_Position = cellToClip(aPosition);
}
)";
const char* const kDepthFragment = R"(
noperspective in float vDepth;
out vec4 depth;
void main() { depth = vec4(vDepth, 0.0, 0.0, 1.0); }
)";

// The warp pass: the proxy at the target pose, every vertex carrying its place in every source.
const char* const kWarpVertex = R"(
layout(location = 0) in vec3 aTarget;
layout(location = 1) in vec3 aSource0;
layout(location = 2) in vec3 aSource1;
layout(location = 3) in vec3 aSource2;
layout(location = 4) in vec3 aSource3;
noperspective out vec3 vSource0;
noperspective out vec3 vSource1;
noperspective out vec3 vSource2;
noperspective out vec3 vSource3;
void main() {
    vSource0 = aSource0;
    vSource1 = aSource1;
    vSource2 = aSource2;
    vSource3 = aSource3;
    gl_Position = cellToClip(aTarget);
}
)";

// Mirrors warpProxy()'s per-pixel loop (ProxyWarp.cpp) without the rim and normal weighting.
const char* const kWarpFragment = R"(
uniform sampler2DArray uCells;   // source k's image in layer uLayers[k], rows top first
uniform ivec4 uLayers;
uniform sampler2DArray uDepths;  // source k's nearest depth in layer k
uniform int uCount;
uniform float uWeights[4];
uniform float uWeightSum;
uniform float uTolerance;
uniform float uDistrust;
uniform bool uOpaque;
noperspective in vec3 vSource0;
noperspective in vec3 vSource1;
noperspective in vec3 vSource2;
noperspective in vec3 vSource3;
out vec4 colour;

vec4 texel(int image, ivec2 p) {
    int size = int(uSize);
    if (p.x < 0 || p.y < 0 || p.x >= size || p.y >= size) return vec4(0.0);
    return texelFetch(uCells, ivec3(p, uLayers[image]), 0);
}

#include_sample

vec3 source(int k) { return k == 0 ? vSource0 : k == 1 ? vSource1 : k == 2 ? vSource2 : vSource3; }

void main() {
    int size = int(uSize);
    float w[4] = float[4](0.0, 0.0, 0.0, 0.0);
    float sum = 0.0;
    for (int k = 0; k < 4; ++k) {
        if (k >= uCount) break;
        vec3 q = source(k);
        int qx = int(floor(q.x)), qy = int(floor(q.y));
        bool visible = true;
        if (qx >= 0 && qy >= 0 && qx < size && qy < size) {
            float front = texelFetch(uDepths, ivec3(qx, qy, k), 0).r;
            visible = front < -1e29 || q.z >= front - uTolerance;
        }
        w[k] = uWeights[k] * (visible ? 1.0 : uDistrust);
        sum += w[k];
    }
    if (!(sum > 0.0)) {
        sum = uWeightSum;
        for (int k = 0; k < 4; ++k) w[k] = k < uCount ? uWeights[k] : 0.0;
    }
    vec4 c = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        if (k >= uCount) break;
        if (w[k] <= 0.0) continue;
        c += samplePremultiplied(k, source(k).xy) * (w[k] / sum);
    }
    if (uOpaque && c.a > 1e-3) c = vec4(c.rgb / c.a, 1.0);
    colour = clamp(c, 0.0, 1.0);
}
)";

std::string withSampling(const char* text) {
    std::string s = text;
    const std::string mark = "#include_sample";
    const std::size_t at = s.find(mark);
    if (at != std::string::npos) s.replace(at, mark.size(), detail::kGlslSamplePremultiplied);
    return s;
}

}  // namespace

struct GpuProxyWarper::Impl {
    std::shared_ptr<GlContext> context;  // first member: destroyed last
    std::unique_ptr<ShaderProgram> depthProgram, warpProgram;
    GLuint vao = 0, vertices = 0, indices = 0;
    GLuint depthFbo = 0, warpFbo = 0, depthBuffer = 0, depths = 0, cells = 0, target = 0;
    int size = 0;

    // (Re)makes the size-dependent textures and framebuffers for cells of `s` pixels.
    void resize(int s) {
        if (s == size) return;
        const GladGLContext& gl = context->gl();
        gl.BindRenderbuffer(GL_RENDERBUFFER, depthBuffer);
        gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, s, s);
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, depths);
        gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32F, s, s, kSources, 0, GL_RED, GL_FLOAT, nullptr);
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, cells);
        gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, s, s, kSources, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        gl.BindTexture(GL_TEXTURE_2D, target);
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, s, s, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        gl.BindFramebuffer(GL_FRAMEBUFFER, warpFbo);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, 0);
        gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer);
        if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("GpuProxyWarper: the warp framebuffer is incomplete");
        size = s;
    }

    // Draws the warp of `sources` (layers of `cellsTexture`) into `target` through warpFbo.
    void draw(const ProxyMesh& mesh, GLuint cellsTexture, std::span<const LayerSource> sources, const glm::vec3& toEye, double keyframe,
              float weightSum, const ProxyWarpOptions& options);

    // Points attribute `location` at the projection of slot `slot` (0 the target, 1 + k source k).
    void attribute(GLuint location, int slot) const {
        const GladGLContext& gl = context->gl();
        gl.EnableVertexAttribArray(location);
        gl.VertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float),
                               reinterpret_cast<const void*>(static_cast<std::size_t>(slot) * 3 * sizeof(float)));
    }
};

GpuProxyWarper::GpuProxyWarper(std::shared_ptr<GlContext> context) {
    if (!context) throw std::invalid_argument("GpuProxyWarper: argument 'context' is null");
    impl_ = std::make_unique<Impl>();
    Impl& s = *impl_;
    s.context = std::move(context);
    s.context->makeCurrent();
    const GladGLContext& gl = s.context->gl();
    const std::string head = std::string("#version 330 core\n") + kProjection;
    s.depthProgram = std::make_unique<ShaderProgram>(*s.context, "GpuProxyWarper depth shader", head + kDepthVertex,
                                                     std::string("#version 330 core\n") + kDepthFragment);
    s.warpProgram = std::make_unique<ShaderProgram>(*s.context, "GpuProxyWarper warp shader", head + kWarpVertex,
                                                    head + withSampling(kWarpFragment));
    gl.GenVertexArrays(1, &s.vao);
    gl.GenBuffers(1, &s.vertices);
    gl.GenBuffers(1, &s.indices);
    gl.GenFramebuffers(1, &s.depthFbo);
    gl.GenFramebuffers(1, &s.warpFbo);
    gl.GenRenderbuffers(1, &s.depthBuffer);
    gl.GenTextures(1, &s.depths);
    gl.GenTextures(1, &s.cells);
    gl.GenTextures(1, &s.target);
    for (GLuint tex : {s.depths, s.cells}) {
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, tex);
        gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    gl.UseProgram(s.warpProgram->id());
    gl.Uniform1i(s.warpProgram->uniformLocation("uCells"), 0);
    gl.Uniform1i(s.warpProgram->uniformLocation("uDepths"), 1);
    gl.UseProgram(0);
}

GpuProxyWarper::~GpuProxyWarper() {
    Impl& s = *impl_;
    try {
        s.context->makeCurrent();
    } catch (...) {
        return;  // the context is gone: so are its objects
    }
    const GladGLContext& gl = s.context->gl();
    const GLuint textures[3] = {s.depths, s.cells, s.target};
    gl.DeleteTextures(3, textures);
    gl.DeleteRenderbuffers(1, &s.depthBuffer);
    gl.DeleteFramebuffers(1, &s.depthFbo);
    gl.DeleteFramebuffers(1, &s.warpFbo);
    const GLuint buffers[2] = {s.vertices, s.indices};
    gl.DeleteBuffers(2, buffers);
    gl.DeleteVertexArrays(1, &s.vao);
    s.depthProgram.reset();
    s.warpProgram.reset();
}

namespace {

// The options the GPU does not draw, refused by name; the source count.
void checkGpuOptions(std::size_t sources, const ProxyWarpOptions& options, const char* who) {
    const std::string w(who);
    if (sources > GpuProxyWarper::kMaxSources)
        throw std::invalid_argument(w + ": " + std::to_string(sources) + " sources, at most " + std::to_string(GpuProxyWarper::kMaxSources));
    if (options.rim > 0) throw std::invalid_argument(w + ": a rim is not drawn on the GPU (rim must be 0)");
    if (options.normalSharpness > 0.0f)
        throw std::invalid_argument(w + ": normal weighting is not drawn on the GPU (normalSharpness must be 0)");
    if (options.bicubic) throw std::invalid_argument(w + ": bicubic sampling is not drawn on the GPU");
}

}  // namespace

Image GpuProxyWarper::warp(const ProxyMesh& mesh, std::span<const ProxySource> sources, const glm::vec3& toEye, double keyframe,
                           const ProxyWarpOptions& options) {
    const float weightSum = checkProxyWarp(mesh, sources, keyframe, options, "GpuProxyWarper::warp");
    checkGpuOptions(sources.size(), options, "GpuProxyWarper::warp");
    Impl& s = *impl_;
    s.context->makeCurrent();
    const GladGLContext& gl = s.context->gl();
    const int size = mesh.cellSize();
    s.resize(size);
    // The sources' images, layer by layer.
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, s.cells);
    std::vector<LayerSource> layers;
    for (std::size_t k = 0; k < sources.size(); ++k) {
        gl.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, static_cast<GLint>(k), size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                         sources[k].image->rgba.data());
        layers.push_back({static_cast<int>(k), sources[k].toEye, sources[k].keyframe, sources[k].weight});
    }
    s.draw(mesh, s.cells, layers, toEye, keyframe, weightSum, options);
    Image out;
    out.name = "proxy warp (GL)";
    out.width = out.height = size;
    out.rgba.resize(static_cast<std::size_t>(size) * size * 4);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.ReadPixels(0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());  // GL rows are image rows
    gl.BindFramebuffer(GL_FRAMEBUFFER, s.context->drawTarget().framebuffer);
    return out;
}

void GpuProxyWarper::warpInto(const ProxyMesh& mesh, unsigned cells, std::span<const LayerSource> sources, const glm::vec3& toEye,
                              double keyframe, unsigned target, int targetLayer, const ProxyWarpOptions& options) {
    const char* who = "GpuProxyWarper::warpInto";
    if (cells == 0 || target == 0) throw std::invalid_argument(std::string(who) + ": a texture name is 0");
    if (sources.empty()) throw std::invalid_argument(std::string(who) + ": no source");
    checkGpuOptions(sources.size(), options, who);
    float weightSum = 0.0f;
    for (std::size_t k = 0; k < sources.size(); ++k) {
        const LayerSource& src = sources[k];
        if (src.layer < 0) throw std::invalid_argument(std::string(who) + ": source " + std::to_string(k) + " has a negative layer");
        if (src.keyframe < 0 || src.keyframe >= mesh.keyframeCount())
            throw std::invalid_argument(std::string(who) + ": source " + std::to_string(k) + " key-frame out of range");
        if (!(src.weight >= 0.0f) || !std::isfinite(src.weight))
            throw std::invalid_argument(std::string(who) + ": source " + std::to_string(k) + " has a negative or non-finite weight");
        weightSum += src.weight;
    }
    if (!(weightSum > 0.0f)) throw std::invalid_argument(std::string(who) + ": the source weights sum to zero");
    if (!std::isfinite(keyframe)) throw std::invalid_argument(std::string(who) + ": the target key-frame is not finite");
    if (!(options.depthTolerance >= 0.0f) || !(options.distrust >= 0.0f && options.distrust <= 1.0f))
        throw std::invalid_argument(std::string(who) + ": depth tolerance must be >= 0, distrust in [0, 1]");
    Impl& s = *impl_;
    s.context->makeCurrent();
    const GladGLContext& gl = s.context->gl();
    const int size = mesh.cellSize();
    detail::checkLayerFits(gl, target, targetLayer, size, who);
    s.resize(size);
    // Drawn into the warper's own texture, then copied into the layer by the GL: the target may be
    // the very array the sources are read from.
    s.draw(mesh, cells, sources, toEye, keyframe, weightSum, options);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, target);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.CopyTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, targetLayer, 0, 0, size, size);
    gl.BindFramebuffer(GL_FRAMEBUFFER, s.context->drawTarget().framebuffer);
}

void GpuProxyWarper::Impl::draw(const ProxyMesh& mesh, GLuint cellsTexture, std::span<const LayerSource> sources, const glm::vec3& toEye,
                                 double keyframe, float weightSum, const ProxyWarpOptions& options) {
    Impl& s = *this;
    const GladGLContext& gl = s.context->gl();
    const int cellSize = mesh.cellSize();
    // The state the drawing changes, given back at the end: the renderer that calls this between its
    // passes clears and draws with its own.
    GLfloat clearColour[4], clearDepth = 1.0f;
    GLint viewport[4], depthFunc = GL_LESS, depthMask = GL_TRUE, boundArrays[2] = {0, 0};
    gl.GetFloatv(GL_COLOR_CLEAR_VALUE, clearColour);
    gl.GetFloatv(GL_DEPTH_CLEAR_VALUE, &clearDepth);
    gl.GetIntegerv(GL_VIEWPORT, viewport);
    gl.GetIntegerv(GL_DEPTH_FUNC, &depthFunc);
    gl.GetIntegerv(GL_DEPTH_WRITEMASK, &depthMask);
    const bool depthTest = gl.IsEnabled(GL_DEPTH_TEST), blend = gl.IsEnabled(GL_BLEND), cull = gl.IsEnabled(GL_CULL_FACE);
    for (int unit = 0; unit < 2; ++unit) {
        gl.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &boundArrays[unit]);
    }
    // Every vertex: where the target pose puts it, then where each source's pose does.
    const std::size_t n = mesh.vertexCount();
    std::vector<float> packed(n * kFloatsPerVertex, 0.0f);
    const auto put = [&](const std::vector<glm::vec3>& p, int slot) {
        for (std::size_t v = 0; v < n; ++v)
            for (int c = 0; c < 3; ++c) packed[v * kFloatsPerVertex + static_cast<std::size_t>(slot) * 3 + static_cast<std::size_t>(c)] = p[v][c];
    };
    put(mesh.project(keyframe, toEye), 0);
    for (std::size_t k = 0; k < sources.size(); ++k) put(mesh.project(sources[k].keyframe, sources[k].toEye), static_cast<int>(k) + 1);
    std::vector<std::uint32_t> triangles;
    triangles.reserve(mesh.triangles().size() * 3);
    for (const auto& t : mesh.triangles()) triangles.insert(triangles.end(), t.begin(), t.end());
    const auto count = static_cast<GLsizei>(triangles.size());

    gl.BindVertexArray(s.vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, s.vertices);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(packed.size() * sizeof(float)), packed.data(), GL_STREAM_DRAW);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.indices);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size() * sizeof(std::uint32_t)), triangles.data(),
                  GL_STREAM_DRAW);
    gl.Viewport(0, 0, cellSize, cellSize);
    gl.Disable(GL_BLEND);
    gl.Disable(GL_CULL_FACE);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_TRUE);
    const float depthRange = 8.0f * static_cast<float>(cellSize);  // beyond any depth of a proxy inside its cell
    // Depth of the nearest surface in every source.
    gl.UseProgram(s.depthProgram->id());
    gl.Uniform1f(s.depthProgram->uniformLocation("uSize"), static_cast<float>(cellSize));
    gl.Uniform1f(s.depthProgram->uniformLocation("uDepthRange"), depthRange);
    gl.BindFramebuffer(GL_FRAMEBUFFER, s.depthFbo);
    for (std::size_t k = 0; k < sources.size(); ++k) {
        gl.FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, s.depths, 0, static_cast<GLint>(k));
        gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s.depthBuffer);
        if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("GpuProxyWarper: the depth framebuffer is incomplete");
        gl.ClearColor(kEmptyDepth, 0.0f, 0.0f, 1.0f);
        gl.ClearDepth(1.0);
        gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        s.attribute(0, static_cast<int>(k) + 1);
        gl.DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
    }
    // The warp at the target pose.
    gl.UseProgram(s.warpProgram->id());
    const ShaderProgram& p = *s.warpProgram;
    gl.Uniform1f(p.uniformLocation("uSize"), static_cast<float>(cellSize));
    gl.Uniform1f(p.uniformLocation("uDepthRange"), depthRange);
    gl.Uniform1i(p.uniformLocation("uCount"), static_cast<GLint>(sources.size()));
    float weights[kSources] = {};
    GLint layers[kSources] = {};
    for (std::size_t k = 0; k < sources.size(); ++k) weights[k] = sources[k].weight, layers[k] = sources[k].layer;
    gl.Uniform1fv(p.uniformLocation("uWeights"), kSources, weights);
    gl.Uniform4iv(p.uniformLocation("uLayers"), 1, layers);
    gl.Uniform1f(p.uniformLocation("uWeightSum"), weightSum);
    gl.Uniform1f(p.uniformLocation("uTolerance"), options.depthTolerance);
    gl.Uniform1f(p.uniformLocation("uDistrust"), options.distrust);
    gl.Uniform1i(p.uniformLocation("uOpaque"), options.opaqueInside ? 1 : 0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, s.warpFbo);
    gl.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl.ClearDepth(1.0);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, cellsTexture);
    gl.ActiveTexture(GL_TEXTURE1);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, s.depths);
    gl.ActiveTexture(GL_TEXTURE0);
    for (int slot = 0; slot <= kSources; ++slot) s.attribute(static_cast<GLuint>(slot), slot);
    gl.DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
    gl.BindVertexArray(0);
    gl.UseProgram(0);
    gl.ClearColor(clearColour[0], clearColour[1], clearColour[2], clearColour[3]);
    gl.ClearDepth(clearDepth);
    gl.Viewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    gl.DepthFunc(static_cast<GLenum>(depthFunc));
    gl.DepthMask(depthMask ? GL_TRUE : GL_FALSE);
    const auto restore = [&](GLenum what, bool on) { on ? gl.Enable(what) : gl.Disable(what); };
    restore(GL_DEPTH_TEST, depthTest);
    restore(GL_BLEND, blend);
    restore(GL_CULL_FACE, cull);
    for (int unit = 1; unit >= 0; --unit) {
        gl.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, static_cast<GLuint>(boundArrays[unit]));
    }
}

}  // namespace throng
