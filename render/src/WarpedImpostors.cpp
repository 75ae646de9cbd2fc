#include "WarpedImpostors.h"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <glad/gl.h>

#include "throng/render/FeatureTrack.h"
#include "throng/render/GlContext.h"
#include "throng/render/ImpostorAtlas.h"
#include "throng/render/ShaderProgram.h"
#include "Shaders.h"

namespace throng {
namespace {

constexpr float kEmptyDepth = -1e30f;  // a cell's depth where no surface covers it

// Shared by both programs: proxy positions and where a point of the actor frame lands in a cell of
// view `view` (x, y in cell pixels, rows down; z the depth towards that view's eye in pixels), as
// ProxyMesh::project puts it.
const char* const kCommon = R"(#version 330 core
uniform sampler2D uPositions;  // x: vertex, y: key-frame
uniform sampler2D uBases;      // x: view, y: 0 right, 1 up, 2 towards the eye
uniform vec3 uCentre;
uniform float uRadius;
uniform float uSize;
vec3 at(int keyframe) { return texelFetch(uPositions, ivec2(gl_VertexID, keyframe), 0).xyz; }
// (right, up and towards the eye: viewBasis's; towards the eye is right x up.)
vec3 inCell(vec3 right, vec3 up, vec3 p) {
    vec3 r = p - uCentre;
    return vec3((dot(right, r) / uRadius * 0.5 + 0.5) * uSize, (0.5 - 0.5 * dot(up, r) / uRadius) * uSize,
                dot(cross(right, up), r) * uSize / (2.0 * uRadius));
}
vec3 inCell(int view, vec3 p) {
    return inCell(texelFetch(uBases, ivec2(view, 0), 0).xyz, texelFetch(uBases, ivec2(view, 1), 0).xyz, p);
}
)";

const char* const kWarpVertex = R"(
layout(location = 0) in vec4 iOriginPhase;
layout(location = 1) in vec3 iAxisX;
layout(location = 2) in vec3 iAxisY;
layout(location = 3) in vec3 iAxisZ;
layout(location = 4) in vec3 iLayers;
layout(location = 5) in vec3 iKeyframes;
layout(location = 6) in vec3 iWeights;
layout(location = 7) in vec4 iTint;
layout(location = 8) in vec3 iRight0;  // each source view's image axes (per instance: no fetch per vertex)
layout(location = 9) in vec3 iUp0;
layout(location = 10) in vec3 iRight1;
layout(location = 11) in vec3 iUp1;
layout(location = 12) in vec3 iRight2;
layout(location = 13) in vec3 iUp2;
layout(location = 14) in vec3 iRegionLayers;
layout(location = 15) in uvec4 iLook;
uniform int uKeyframes;
uniform mat4 uViewRotationProjection;
out vec3 vSource0;
out vec3 vSource1;
out vec3 vSource2;
flat out vec3 vLayers;
flat out vec3 vWeights;
flat out vec4 vTint;
flat out vec3 vRegionLayers;
flat out uvec4 vLook;
void main() {
    float phase = iOriginPhase.w;
    int k0 = int(floor(phase));
    float t = phase - float(k0);
    k0 = ((k0 % uKeyframes) + uKeyframes) % uKeyframes;
    vec3 p = mix(at(k0), at((k0 + 1) % uKeyframes), t);  // the pose at the actor's own clip time
    vec3 world = iOriginPhase.xyz + iAxisX * p.x + iAxisY * p.y + iAxisZ * p.z;
    gl_Position = uViewRotationProjection * vec4(world, 1.0);
    vSource0 = inCell(iRight0, iUp0, at(int(iKeyframes.x)));
    vSource1 = inCell(iRight1, iUp1, at(int(iKeyframes.y)));
    vSource2 = inCell(iRight2, iUp2, at(int(iKeyframes.z)));
    vLayers = iLayers;
    vWeights = iWeights;
    vTint = iTint;
    vRegionLayers = iRegionLayers;
    vLook = iLook;
}
)";

// The fragment shader, with body regions recoloured as ImpostorRenderer's quads do.
std::string warpFragment() {
    return std::string(R"(#version 330 core
uniform sampler2DArray uCells;   // colour layers, rows top first
uniform sampler2DArray uDepths;  // the proxy's nearest depth in the same layers
uniform sampler2DArray uRegions; // per cell (key-frame * views + view): body regions / 255
uniform bool uHasRegions;
uniform float uSize;
uniform float uTolerance;
uniform float uDistrust;
in vec3 vSource0;
in vec3 vSource1;
in vec3 vSource2;
flat in vec3 vLayers;
flat in vec3 vWeights;
flat in vec4 vTint;
flat in vec3 vRegionLayers;
flat in uvec4 vLook;
out vec4 fragColor;
)") + detail::srgbEncodeGlsl() + detail::bodyLookGlsl() + R"(
// A source is trusted where the surface point is the nearest surface its cell shows there.
float trust(vec3 q, float layer) {
    ivec2 p = ivec2(floor(q.xy));
    int size = int(uSize);
    if (p.x < 0 || p.y < 0 || p.x >= size || p.y >= size) return 1.0;
    float front = texelFetch(uDepths, ivec3(p, int(layer)), 0).r;
    return front < -1e29 || q.z >= front - uTolerance ? 1.0 : uDistrust;
}
vec4 cell(vec3 q, float layer) { return texture(uCells, vec3(q.xy / uSize, layer)); }
vec3 paint(vec3 q, float layer) { return regionPaint(uRegions, vec3(q.xy / uSize, layer), vLook); }
void main() {
    vec3 w = vWeights * vec3(trust(vSource0, vLayers.x), trust(vSource1, vLayers.y), trust(vSource2, vLayers.z));
    float sum = w.x + w.y + w.z;
    if (!(sum > 0.0)) {
        w = vWeights;
        sum = w.x + w.y + w.z;
    }
    vec4 c0 = cell(vSource0, vLayers.x);
    vec4 c = w.x * c0;
    vec3 p = vec3(0.0);
    if (uHasRegions) p += w.x * c0.a * paint(vSource0, vRegionLayers.x);
    if (w.y > 0.0) {
        vec4 c1 = cell(vSource1, vLayers.y);
        c += w.y * c1;
        if (uHasRegions) p += w.y * c1.a * paint(vSource1, vRegionLayers.y);
    }
    if (w.z > 0.0) {
        vec4 c2 = cell(vSource2, vLayers.z);
        c += w.z * c2;
        if (uHasRegions) p += w.z * c2.a * paint(vSource2, vRegionLayers.z);
    }
    if (c.a < 0.5 * sum) discard;  // alpha test, as the quads: the cells' outline, not the proxy's
    vec3 rgb = c.rgb / c.a;
    if (uHasRegions) rgb = wearLook(c, p);
    fragColor = vec4(rgb * vTint.rgb, 1.0);
}
)";
}

// The depth pass: the proxy at one key-frame seen from one view, into one layer; pixel rows as
// the cells' (GL row j is image row j), the nearest surface winning.
const char* const kDepthVertex = R"(
uniform int uKeyframe;
uniform int uView;
noperspective out float vDepth;
void main() {
    vec3 q = inCell(uView, at(uKeyframe));
    vDepth = q.z;
    gl_Position = vec4(q.x / uSize * 2.0 - 1.0, q.y / uSize * 2.0 - 1.0, clamp(-q.z / (8.0 * uSize), -1.0, 1.0), 1.0);
}
)";

const char* const kDepthFragment = R"(#version 330 core
noperspective in float vDepth;
out vec4 depth;
void main() { depth = vec4(vDepth, 0.0, 0.0, 1.0); }
)";

void setNearest(const GladGLContext& gl, GLenum target) {
    gl.TexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

// The uniforms both programs share.
void setCommon(const GladGLContext& gl, const ShaderProgram& p, const ImpostorAtlas& atlas, const WarpedAtlasGpu& gpu) {
    gl.Uniform1i(p.uniformLocation("uPositions"), 2);
    gl.Uniform1i(p.uniformLocation("uBases"), 3);
    const glm::vec3& c = atlas.worldCentre();
    gl.Uniform3f(p.uniformLocation("uCentre"), c.x, c.y, c.z);
    gl.Uniform1f(p.uniformLocation("uRadius"), atlas.worldRadius());
    gl.Uniform1f(p.uniformLocation("uSize"), static_cast<float>(atlas.cellSize()));
    gl.ActiveTexture(GL_TEXTURE2);
    gl.BindTexture(GL_TEXTURE_2D, gpu.positions);
    gl.ActiveTexture(GL_TEXTURE3);
    gl.BindTexture(GL_TEXTURE_2D, gpu.bases);
    gl.ActiveTexture(GL_TEXTURE0);
}

}  // namespace

WarpedImpostorPass::WarpedImpostorPass(GlContext& context) : context_(context) {
    const GladGLContext& gl = context_.gl();
    warp_ = std::make_unique<ShaderProgram>(context_, "ImpostorRenderer warped-impostor shader", std::string(kCommon) + kWarpVertex,
                                            warpFragment());
    depth_ = std::make_unique<ShaderProgram>(context_, "ImpostorRenderer proxy-depth shader", std::string(kCommon) + kDepthVertex,
                                             kDepthFragment);
    gl.GenVertexArrays(1, &vao_);
    gl.GenVertexArrays(1, &depthVao_);
    gl.GenBuffers(1, &instanceBuffer_);
    gl.GenFramebuffers(1, &fbo_);
    gl.GenRenderbuffers(1, &depthBuffer_);
    gl.BindVertexArray(vao_);
    gl.BindBuffer(GL_ARRAY_BUFFER, instanceBuffer_);
    const auto stride = static_cast<GLsizei>(sizeof(WarpedInstance));
    const auto attribute = [&](GLuint location, GLint size, std::size_t offset) {
        gl.EnableVertexAttribArray(location);
        gl.VertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offset));
        gl.VertexAttribDivisor(location, 1);
    };
    attribute(0, 4, offsetof(WarpedInstance, originPhase));
    attribute(1, 3, offsetof(WarpedInstance, axisX));
    attribute(2, 3, offsetof(WarpedInstance, axisY));
    attribute(3, 3, offsetof(WarpedInstance, axisZ));
    attribute(4, 3, offsetof(WarpedInstance, layers));
    attribute(5, 3, offsetof(WarpedInstance, keyframes));
    attribute(6, 3, offsetof(WarpedInstance, weights));
    attribute(7, 4, offsetof(WarpedInstance, tint));
    for (GLuint s = 0; s < 3; ++s) {
        attribute(8 + 2 * s, 3, offsetof(WarpedInstance, axes) + s * 6 * sizeof(float));
        attribute(9 + 2 * s, 3, offsetof(WarpedInstance, axes) + (s * 6 + 3) * sizeof(float));
    }
    attribute(14, 3, offsetof(WarpedInstance, regionLayers));
    gl.EnableVertexAttribArray(15);
    gl.VertexAttribIPointer(15, 4, GL_UNSIGNED_INT, stride, reinterpret_cast<void*>(offsetof(WarpedInstance, look)));
    gl.VertexAttribDivisor(15, 1);
    gl.BindVertexArray(0);
    gl.UseProgram(warp_->id());
    gl.Uniform1i(warp_->uniformLocation("uCells"), 0);
    gl.Uniform1i(warp_->uniformLocation("uDepths"), 1);
    gl.Uniform1i(warp_->uniformLocation("uRegions"), 4);
    gl.UseProgram(0);
}

WarpedImpostorPass::~WarpedImpostorPass() {
    const GladGLContext& gl = context_.gl();
    gl.DeleteBuffers(1, &instanceBuffer_);
    gl.DeleteVertexArrays(1, &vao_);
    gl.DeleteVertexArrays(1, &depthVao_);
    gl.DeleteFramebuffers(1, &fbo_);
    gl.DeleteRenderbuffers(1, &depthBuffer_);
}

WarpedAtlasGpu WarpedImpostorPass::upload(const ImpostorAtlas& atlas, int layers) {
    const ProxyMesh* proxy = atlas.drawProxy().get();
    if (!proxy) throw std::invalid_argument("WarpedImpostorPass: atlas '" + atlas.templateName() + "' has no surface proxy");
    const GladGLContext& gl = context_.gl();
    WarpedAtlasGpu g;
    g.keyframes = proxy->keyframeCount();
    g.layers = layers;
    const auto n = static_cast<GLsizei>(proxy->vertexCount());
    std::vector<float> positions;
    positions.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(g.keyframes) * 3);
    for (int k = 0; k < g.keyframes; ++k)
        for (const glm::vec3& p : proxy->positions(k)) positions.insert(positions.end(), {p.x, p.y, p.z});
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.GenTextures(1, &g.positions);
    gl.BindTexture(GL_TEXTURE_2D, g.positions);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, n, g.keyframes, 0, GL_RGB, GL_FLOAT, positions.data());
    setNearest(gl, GL_TEXTURE_2D);
    const std::uint32_t views = atlas.views().viewCount();
    std::vector<float> bases(static_cast<std::size_t>(views) * 9);
    for (std::uint32_t v = 0; v < views; ++v) {
        const ViewBasis b = viewBasis(atlas.views().direction(v));
        const glm::vec3 rows[3] = {b.right, b.up, b.toEye};
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) bases[(static_cast<std::size_t>(r) * views + v) * 3 + static_cast<std::size_t>(c)] = rows[r][c];
    }
    gl.GenTextures(1, &g.bases);
    gl.BindTexture(GL_TEXTURE_2D, g.bases);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, static_cast<GLsizei>(views), 3, 0, GL_RGB, GL_FLOAT, bases.data());
    setNearest(gl, GL_TEXTURE_2D);
    std::vector<std::uint32_t> indices;
    indices.reserve(proxy->triangles().size() * 3);
    for (const auto& t : proxy->triangles()) indices.insert(indices.end(), t.begin(), t.end());
    g.indexCount = static_cast<int>(indices.size());
    gl.GenBuffers(1, &g.triangles);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.triangles);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(), GL_STATIC_DRAW);
    g.bytes = (positions.size() + bases.size()) * sizeof(float) + indices.size() * sizeof(std::uint32_t);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    const int s = atlas.cellSize();
    gl.GenTextures(1, &g.depths);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.depths);
    std::vector<float> empty(static_cast<std::size_t>(s) * static_cast<std::size_t>(s) * static_cast<std::size_t>(std::max(layers, 1)), kEmptyDepth);
    gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32F, s, s, std::max(layers, 1), 0, GL_RED, GL_FLOAT, empty.data());
    setNearest(gl, GL_TEXTURE_2D_ARRAY);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);
    return g;
}

void WarpedImpostorPass::setViews(const ImpostorAtlas& atlas, WarpedInstance& w, const float views[3]) {
    for (int i = 0; i < 3; ++i) {
        const ViewBasis b = viewBasis(atlas.views().direction(static_cast<std::uint32_t>(views[i])));
        for (int c = 0; c < 3; ++c) w.axes[i * 6 + c] = b.right[c], w.axes[i * 6 + 3 + c] = b.up[c];
    }
}

void WarpedImpostorPass::release(WarpedAtlasGpu& g) {
    const GladGLContext& gl = context_.gl();
    const GLuint textures[3] = {g.positions, g.bases, g.depths};
    gl.DeleteTextures(3, textures);
    gl.DeleteBuffers(1, &g.triangles);
    g = {};
}

void WarpedImpostorPass::depthInto(const ImpostorAtlas& atlas, WarpedAtlasGpu& g, int layer, std::uint32_t view, int keyframe) {
    if (layer < 0 || layer >= g.layers) throw std::out_of_range("WarpedImpostorPass::depthInto: layer " + std::to_string(layer) + " out of range");
    const GladGLContext& gl = context_.gl();
    const int s = atlas.cellSize();
    GLint framebuffer = 0, viewport[4];
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    gl.GetIntegerv(GL_VIEWPORT, viewport);
    const bool depthTest = gl.IsEnabled(GL_DEPTH_TEST), blend = gl.IsEnabled(GL_BLEND);
    if (depthBufferSize_ != s) {
        gl.BindRenderbuffer(GL_RENDERBUFFER, depthBuffer_);
        gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, s, s);
        depthBufferSize_ = s;
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
    gl.FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, g.depths, 0, layer);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer_);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("WarpedImpostorPass: the depth framebuffer is incomplete");
    const GLfloat empty[4] = {kEmptyDepth, 0.0f, 0.0f, 1.0f}, far = 1.0f;
    gl.ClearBufferfv(GL_COLOR, 0, empty);
    gl.ClearBufferfv(GL_DEPTH, 0, &far);
    gl.Viewport(0, 0, s, s);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_BLEND);
    gl.UseProgram(depth_->id());
    setCommon(gl, *depth_, atlas, g);
    gl.Uniform1i(depth_->uniformLocation("uKeyframe"), keyframe);
    gl.Uniform1i(depth_->uniformLocation("uView"), static_cast<GLint>(view));
    gl.BindVertexArray(depthVao_);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.triangles);
    gl.DrawElements(GL_TRIANGLES, g.indexCount, GL_UNSIGNED_INT, nullptr);
    gl.BindVertexArray(0);
    gl.UseProgram(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(framebuffer));
    gl.Viewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    depthTest ? gl.Enable(GL_DEPTH_TEST) : gl.Disable(GL_DEPTH_TEST);
    blend ? gl.Enable(GL_BLEND) : gl.Disable(GL_BLEND);
}

void WarpedImpostorPass::draw(const ImpostorAtlas& atlas, const WarpedAtlasGpu& g, unsigned cells, unsigned regions,
                              std::span<const WarpedInstance> instances, const glm::mat4& viewRotationProjection) {
    if (instances.empty()) return;
    const GladGLContext& gl = context_.gl();
    gl.UseProgram(warp_->id());
    setCommon(gl, *warp_, atlas, g);
    gl.UniformMatrix4fv(warp_->uniformLocation("uViewRotationProjection"), 1, GL_FALSE, &viewRotationProjection[0][0]);
    gl.Uniform1i(warp_->uniformLocation("uKeyframes"), g.keyframes);
    gl.Uniform1f(warp_->uniformLocation("uTolerance"), 2.0f);  // ProxyWarpOptions' defaults
    gl.Uniform1f(warp_->uniformLocation("uDistrust"), 0.0f);
    gl.Uniform1i(warp_->uniformLocation("uHasRegions"), regions != 0);
    gl.ActiveTexture(GL_TEXTURE4);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, regions);
    gl.ActiveTexture(GL_TEXTURE1);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.depths);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, cells);
    gl.BindVertexArray(vao_);
    gl.BindBuffer(GL_ARRAY_BUFFER, instanceBuffer_);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(instances.size() * sizeof(WarpedInstance)), instances.data(), GL_STREAM_DRAW);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.triangles);
    gl.DrawElementsInstanced(GL_TRIANGLES, g.indexCount, GL_UNSIGNED_INT, nullptr, static_cast<GLsizei>(instances.size()));
    gl.BindVertexArray(0);
    gl.UseProgram(0);
}

}  // namespace throng
