#include "throng/render/GpuMorpher.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <glad/gl.h>

#include "throng/render/GlContext.h"
#include "throng/render/ShaderProgram.h"
#include "GlslSampling.h"
#include "TextureLayerFit.h"

namespace throng {
namespace {

const char* const kVertexShader = R"(#version 330 core
// A triangle covering the viewport; no vertex buffer needed.
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Mirrors BeierNeely.cpp line for line (lineContribution, samplePremultiplied, morphImages).
// Compiled twice: with THRONG_ARRAY_SOURCES both neighbours are layers of one texture array and
// the cell is written into a layer of another (rows top first, as the atlas stores them); without,
// the neighbours are two 2-D textures and the result is read back.
const char* const kFragmentShader = R"(
#ifdef THRONG_ARRAY_SOURCES
uniform sampler2DArray uCells;
uniform ivec2 uLayers;     // from, to
#else
uniform sampler2D uFrom;
uniform sampler2D uTo;
#endif
uniform vec4 uTarget[64];
uniform vec4 uFromLines[64];
uniform vec4 uToLines[64];
uniform vec4 uAttributes[64];  // per target line: weight, capsule radius, depth at p, depth at q
uniform int uCount;
uniform vec3 uParams;      // a, b, p
uniform float uDepth;      // depth order: weight *= exp(uDepth * z)
uniform float uT;
uniform ivec2 uSize;
out vec4 colour;

const float kDegenerate = 1e-3;
const float kMinLength = 1.0;
const float kMaxDepthExponent = 40.0;

vec2 perpendicular(vec2 d) { return vec2(-d.y, d.x); }

vec2 sourcePosition(vec2 x, bool second) {
    vec2 sum = vec2(0.0);
    float weightSum = 0.0;
    for (int i = 0; i < uCount; ++i) {
        vec4 dl = uTarget[i];
        vec4 sl = second ? uToLines[i] : uFromLines[i];
        vec4 at = uAttributes[i];
        vec2 d = dl.zw - dl.xy;
        float len2 = dot(d, d);
        float len = sqrt(len2);
        vec2 xp = x - dl.xy;
        vec2 s = sl.zw - sl.xy;
        float slen = sqrt(dot(s, s));
        vec2 proposed;
        float dist;
        float along = 0.0;
        if (len < kDegenerate || slen < kDegenerate) {
            proposed = sl.xy + xp;
            dist = sqrt(dot(xp, xp));
        } else {
            float u = dot(xp, d) / len2;
            float v = dot(xp, perpendicular(d)) / len;
            proposed = sl.xy + u * s + v * (perpendicular(s) / slen);
            if (u < 0.0) dist = sqrt(dot(xp, xp));
            else if (u > 1.0) { vec2 xq = x - dl.zw; dist = sqrt(dot(xq, xq)); along = 1.0; }
            else { dist = abs(v); along = u; }
        }
        float a = max(uParams.x, 1e-3);
        float lenP = pow(max(len, kMinLength), uParams.z);
        float capsule = max(dist - at.y, 0.0);
        float order = 1.0;
        if (uDepth != 0.0 && capsule <= 0.0) {
            float z = at.z + (at.w - at.z) * along;
            order = exp(clamp(uDepth * z, -kMaxDepthExponent, kMaxDepthExponent));
        }
        float w = pow(lenP / (a + capsule), uParams.y) * (at.x * order);
        sum += (proposed - x) * w;
        weightSum += w;
    }
    if (!(weightSum > 0.0) || isinf(weightSum) || isnan(weightSum)) return x;
    vec2 r = x + sum / weightSum;
    return (any(isnan(r)) || any(isinf(r))) ? x : r;
}

vec4 texel(int image, ivec2 p) {
    if (p.x < 0 || p.y < 0 || p.x >= uSize.x || p.y >= uSize.y) return vec4(0.0);
#ifdef THRONG_ARRAY_SOURCES
    return texelFetch(uCells, ivec3(p, uLayers[image]), 0);
#else
    return image == 0 ? texelFetch(uFrom, p, 0) : texelFetch(uTo, p, 0);
#endif
}

#include_sample

void main() {
#ifdef THRONG_ARRAY_SOURCES
    vec2 x = gl_FragCoord.xy;  // written into a layer whose rows are stored top first
#else
    // Read back top row first; gl_FragCoord counts from the bottom.
    vec2 x = vec2(gl_FragCoord.x, float(uSize.y) - gl_FragCoord.y);
#endif
    vec4 c0 = samplePremultiplied(0, sourcePosition(x, false));
    vec4 c1 = samplePremultiplied(1, sourcePosition(x, true));
    colour = clamp(c0 * (1.0 - uT) + c1 * uT, 0.0, 1.0);
}
)";

std::vector<float> packLines(std::span<const FeatureLine> lines) {
    std::vector<float> out;
    out.reserve(lines.size() * 4);
    for (const FeatureLine& l : lines) out.insert(out.end(), {l.p.x, l.p.y, l.q.x, l.q.y});
    return out;
}

void checkLines(const char* where, std::span<const FeatureLine> fromLines, std::span<const FeatureLine> toLines,
                std::span<const FeatureLine> targetLines, float t) {
    if (fromLines.size() != targetLines.size() || toLines.size() != targetLines.size())
        throw std::invalid_argument(std::string(where) + ": the three line sets differ in size");
    if (targetLines.size() > GpuMorpher::kMaxLines)
        throw std::invalid_argument(std::string(where) + ": " + std::to_string(targetLines.size()) + " lines, at most " +
                                    std::to_string(GpuMorpher::kMaxLines));
    if (!std::isfinite(t)) throw std::invalid_argument(std::string(where) + ": t is not finite");
}

// One vec4 per line (weight, radius, depth at p, depth at q); the classic line when none is given.
std::vector<float> packAttributes(std::span<const LineAttributes> attributes, std::size_t lines) {
    std::vector<float> out;
    out.reserve(lines * 4);
    for (std::size_t i = 0; i < lines; ++i) {
        const LineAttributes a = i < attributes.size() ? attributes[i] : LineAttributes{};
        out.insert(out.end(), {a.weight, a.radius, a.depthP, a.depthQ});
    }
    return out;
}

}  // namespace

struct GpuMorpher::Impl {
    std::shared_ptr<GlContext> context;  // first member: destroyed last
    std::unique_ptr<ShaderProgram> program;       // 2-D sources, read back
    std::unique_ptr<ShaderProgram> arrayProgram;  // layers of a texture array, written into a layer
    GLuint vao = 0, fbo = 0, layerFbo = 0, target = 0, scratch = 0, sources[2] = {0, 0};
    int width = 0, height = 0, scratchSize = 0;

    // Sets the line and blend uniforms of `p` and draws the full-cell triangle into the bound
    // framebuffer.
    void drawCell(const ShaderProgram& p, std::span<const FeatureLine> fromLines, std::span<const FeatureLine> toLines,
                  std::span<const FeatureLine> targetLines, float t, const MorphParameters& parameters,
                  std::span<const LineAttributes> attributes, int w, int h) {
        const GladGLContext& gl = context->gl();
        gl.UseProgram(p.id());
        const auto n = static_cast<GLsizei>(targetLines.size());
        if (n > 0) {
            gl.Uniform4fv(p.uniformLocation("uTarget"), n, packLines(targetLines).data());
            gl.Uniform4fv(p.uniformLocation("uFromLines"), n, packLines(fromLines).data());
            gl.Uniform4fv(p.uniformLocation("uToLines"), n, packLines(toLines).data());
            gl.Uniform4fv(p.uniformLocation("uAttributes"), n, packAttributes(attributes, targetLines.size()).data());
        }
        gl.Uniform1f(p.uniformLocation("uDepth"), parameters.depth);
        gl.Uniform1i(p.uniformLocation("uCount"), n);
        gl.Uniform3f(p.uniformLocation("uParams"), parameters.a, parameters.b, parameters.p);
        gl.Uniform1f(p.uniformLocation("uT"), t);
        gl.Uniform2i(p.uniformLocation("uSize"), w, h);
        gl.Viewport(0, 0, w, h);
        gl.Disable(GL_BLEND);
        gl.Disable(GL_DEPTH_TEST);
        gl.Disable(GL_CULL_FACE);
        gl.BindVertexArray(vao);
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
        gl.BindVertexArray(0);
    }
};

GpuMorpher::GpuMorpher(std::shared_ptr<GlContext> context) {
    if (!context) throw std::invalid_argument("GpuMorpher: argument 'context' is null");
    impl_ = std::make_unique<Impl>();
    Impl& s = *impl_;
    s.context = std::move(context);
    s.context->makeCurrent();
    const GladGLContext& gl = s.context->gl();
    const std::string version = "#version 330 core\n";
    std::string fragment = kFragmentShader;
    fragment.replace(fragment.find("#include_sample"), std::string("#include_sample").size(), detail::kGlslSamplePremultiplied);
    s.program = std::make_unique<ShaderProgram>(*s.context, "GpuMorpher shader", kVertexShader, version + fragment);
    s.arrayProgram = std::make_unique<ShaderProgram>(*s.context, "GpuMorpher array shader", kVertexShader,
                                                     version + "#define THRONG_ARRAY_SOURCES\n" + fragment);
    gl.GenVertexArrays(1, &s.vao);
    gl.GenFramebuffers(1, &s.fbo);
    gl.GenFramebuffers(1, &s.layerFbo);
    gl.GenTextures(1, &s.target);
    gl.GenTextures(1, &s.scratch);
    gl.GenTextures(2, s.sources);
    for (GLuint tex : s.sources) {
        gl.BindTexture(GL_TEXTURE_2D, tex);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    gl.UseProgram(s.program->id());
    gl.Uniform1i(s.program->uniformLocation("uFrom"), 0);
    gl.Uniform1i(s.program->uniformLocation("uTo"), 1);
    gl.UseProgram(s.arrayProgram->id());
    gl.Uniform1i(s.arrayProgram->uniformLocation("uCells"), 0);
    gl.UseProgram(0);
}

GpuMorpher::~GpuMorpher() {
    Impl& s = *impl_;
    try {
        s.context->makeCurrent();
    } catch (...) {
        return;  // the context is gone: so are its objects
    }
    const GladGLContext& gl = s.context->gl();
    gl.DeleteTextures(2, s.sources);
    gl.DeleteTextures(1, &s.target);
    gl.DeleteTextures(1, &s.scratch);
    gl.DeleteFramebuffers(1, &s.fbo);
    gl.DeleteFramebuffers(1, &s.layerFbo);
    gl.DeleteVertexArrays(1, &s.vao);
    s.program.reset();
    s.arrayProgram.reset();
}

Image GpuMorpher::morph(const Image& from, std::span<const FeatureLine> fromLines, const Image& to,
                        std::span<const FeatureLine> toLines, std::span<const FeatureLine> targetLines, float t,
                        const MorphParameters& parameters, std::span<const LineAttributes> attributes) {
    if (!from.valid() || !to.valid()) throw std::invalid_argument("GpuMorpher::morph: an image is invalid");
    if (from.width != to.width || from.height != to.height)
        throw std::invalid_argument("GpuMorpher::morph: images of different sizes");
    checkLines("GpuMorpher::morph", fromLines, toLines, targetLines, t);
    checkLineAttributes(attributes, targetLines.size(), "GpuMorpher::morph");
    if (!std::isfinite(parameters.depth)) throw std::invalid_argument("GpuMorpher::morph: the depth parameter is not finite");

    Impl& s = *impl_;
    s.context->makeCurrent();
    const GladGLContext& gl = s.context->gl();
    const int w = from.width, h = from.height;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s.fbo);
    if (w != s.width || h != s.height) {
        gl.BindTexture(GL_TEXTURE_2D, s.target);
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s.target, 0);
        if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("GpuMorpher::morph: the target framebuffer is incomplete");
        s.width = w;
        s.height = h;
    }
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const Image* images[2] = {&from, &to};
    for (int i = 0; i < 2; ++i) {
        gl.ActiveTexture(GL_TEXTURE0 + i);
        gl.BindTexture(GL_TEXTURE_2D, s.sources[i]);
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, images[i]->rgba.data());
    }
    gl.ActiveTexture(GL_TEXTURE0);
    s.drawCell(*s.program, fromLines, toLines, targetLines, t, parameters, attributes, w, h);

    Image out;
    out.name = from.name + "~" + to.name;
    out.width = w;
    out.height = h;
    out.rgba.resize(static_cast<std::size_t>(w) * h * 4);
    std::vector<std::uint8_t> flipped(out.rgba.size());
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
    const std::size_t row = static_cast<std::size_t>(w) * 4;
    for (int y = 0; y < h; ++y)
        std::copy_n(flipped.data() + static_cast<std::size_t>(h - 1 - y) * row, row, out.rgba.data() + y * row);
    gl.UseProgram(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, s.context->drawTarget().framebuffer);
    return out;
}

void GpuMorpher::morphInto(unsigned cells, int fromLayer, int toLayer, unsigned target, int targetLayer, int size,
                           std::span<const FeatureLine> fromLines, std::span<const FeatureLine> toLines,
                           std::span<const FeatureLine> targetLines, float t, const MorphParameters& parameters,
                           std::span<const LineAttributes> attributes) {
    if (cells == 0 || target == 0) throw std::invalid_argument("GpuMorpher::morphInto: a texture name is 0");
    if (fromLayer < 0 || toLayer < 0 || targetLayer < 0 || size <= 0)
        throw std::invalid_argument("GpuMorpher::morphInto: negative layer or size");
    checkLines("GpuMorpher::morphInto", fromLines, toLines, targetLines, t);
    checkLineAttributes(attributes, targetLines.size(), "GpuMorpher::morphInto");
    if (!std::isfinite(parameters.depth)) throw std::invalid_argument("GpuMorpher::morphInto: the depth parameter is not finite");
    Impl& s = *impl_;
    s.context->makeCurrent();
    const GladGLContext& gl = s.context->gl();
    detail::checkLayerFits(gl, target, targetLayer, size, "GpuMorpher::morphInto");
    // Drawn into a scratch texture, then copied into the layer by the GL: the target may be the
    // very array the neighbours are read from (no rendering into a texture being sampled).
    gl.BindFramebuffer(GL_FRAMEBUFFER, s.layerFbo);
    if (size != s.scratchSize) {
        gl.BindTexture(GL_TEXTURE_2D, s.scratch);
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, size, size, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s.scratch, 0);
        if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("GpuMorpher::morphInto: the scratch framebuffer is incomplete");
        s.scratchSize = size;
    }
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, cells);
    gl.UseProgram(s.arrayProgram->id());
    gl.Uniform2i(s.arrayProgram->uniformLocation("uLayers"), fromLayer, toLayer);
    s.drawCell(*s.arrayProgram, fromLines, toLines, targetLines, t, parameters, attributes, size, size);
    gl.UseProgram(0);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, target);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.CopyTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, targetLayer, 0, 0, size, size);
    gl.BindFramebuffer(GL_FRAMEBUFFER, s.context->drawTarget().framebuffer);
}

}  // namespace throng
