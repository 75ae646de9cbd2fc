#include "throng/render/ImpostorRenderer.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <glad/gl.h>
#include <glm/mat3x3.hpp>

#include "throng/render/GlContext.h"
#include "throng/render/ImpostorDrawable.h"
#include "throng/render/ShaderProgram.h"
#include "throng/scenegraph/Camera.h"

namespace throng {
namespace {

const char* const kVertexShader = R"(#version 330 core
// Per instance: centre relative to the eye, half size, tint, three layers and weights.
layout(location = 0) in vec4 iCentreSize;
layout(location = 1) in vec4 iTint;
layout(location = 2) in vec3 iLayers;
layout(location = 3) in vec3 iWeights;
uniform mat4 uViewRotationProjection;  // projection * view rotation (the eye at the origin)
uniform vec3 uRight;
uniform vec3 uUp;
out vec2 vUv;
flat out vec3 vLayers;
flat out vec3 vWeights;
flat out vec4 vTint;
void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
    vec3 p = iCentreSize.xyz + (uRight * corner.x + uUp * corner.y) * iCentreSize.w;
    gl_Position = uViewRotationProjection * vec4(p, 1.0);
    vUv = vec2(0.5 + 0.5 * corner.x, 0.5 - 0.5 * corner.y);  // cells are stored top row first
    vLayers = iLayers;
    vWeights = iWeights;
    vTint = iTint;
}
)";

const char* const kFragmentShader = R"(#version 330 core
uniform sampler2DArray uCells;
in vec2 vUv;
flat in vec3 vLayers;
flat in vec3 vWeights;
flat in vec4 vTint;
out vec4 fragColor;
void main() {
    vec4 c = vWeights.x * texture(uCells, vec3(vUv, vLayers.x));
    if (vWeights.y > 0.0) c += vWeights.y * texture(uCells, vec3(vUv, vLayers.y));
    if (vWeights.z > 0.0) c += vWeights.z * texture(uCells, vec3(vUv, vLayers.z));
    if (c.a < 0.5) discard;  // alpha test: quads write depth like the meshes they replace
    fragColor = vec4(c.rgb / c.a * vTint.rgb, 1.0);  // cells are premultiplied
}
)";

struct Instance {
    float centreSize[4];
    float tint[4];
    float layers[3];
    float weights[3];
};

// One atlas on the GPU: stored cells in layers [0, stored), morphed cells of this frame after.
struct GpuAtlas {
    unsigned texture = 0;
    int layers = 0, stored = 0, cellSize = 0;
    std::vector<int> storedLayer;  // per (keyframe, view): layer, or -1 when dropped
    std::unordered_map<const Image*, int> morphedLayer;  // this frame's morphed cells
    std::vector<Instance> instances;
    std::weak_ptr<const ImpostorAtlas> owner;
};

}  // namespace

struct ImpostorRenderer::Impl {
    std::shared_ptr<GlContext> context;  // first member: destroyed last
    std::unique_ptr<ShaderProgram> program;
    unsigned vao = 0, buffer = 0;
    std::unordered_map<const ImpostorAtlas*, GpuAtlas> atlases;
    ImpostorRenderStatistics stats;
    int maxLayers = 256;
    int morphLayers = 256;

    GpuAtlas& upload(const ImpostorDrawable& d) {
        const ImpostorAtlas& atlas = d.atlas();
        auto it = atlases.find(&atlas);
        if (it != atlases.end() && !it->second.owner.expired()) return it->second;
        const GladGLContext& gl = context->gl();
        GpuAtlas g;
        g.owner = d.atlasPtr();
        g.cellSize = atlas.cellSize();
        const std::uint32_t views = atlas.views().viewCount();
        g.storedLayer.assign(static_cast<std::size_t>(atlas.keyframeCount()) * views, -1);
        for (int k = 0; k < atlas.keyframeCount(); ++k)
            if (atlas.stored(k))
                for (std::uint32_t v = 0; v < views; ++v) g.storedLayer[static_cast<std::size_t>(k) * views + v] = g.stored++;
        g.layers = g.stored + morphLayers;
        if (g.layers > maxLayers)
            throw std::runtime_error("ImpostorRenderer: atlas '" + atlas.templateName() + "' needs " +
                                     std::to_string(g.layers) + " layers, the GL allows " + std::to_string(maxLayers));
        gl.GenTextures(1, &g.texture);
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.texture);
        const int s = atlas.cellSize();
        gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, s, s, g.layers, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        for (int k = 0; k < atlas.keyframeCount(); ++k)
            if (atlas.stored(k))
                for (std::uint32_t v = 0; v < views; ++v) {
                    const Image cell = atlas.cell(v, k);
                    gl.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, g.storedLayer[static_cast<std::size_t>(k) * views + v], s, s,
                                     1, GL_RGBA, GL_UNSIGNED_BYTE, cell.rgba.data());
                }
        ++stats.atlasUploads;
        if (it != atlases.end()) {
            gl.DeleteTextures(1, &it->second.texture);
            atlases.erase(it);
        }
        return atlases.emplace(&atlas, std::move(g)).first->second;
    }
};

ImpostorRenderer::ImpostorRenderer(std::shared_ptr<GlContext> context, int morphLayers) {
    if (!context) throw std::invalid_argument("ImpostorRenderer: argument 'context' is null");
    if (morphLayers < 0) throw std::invalid_argument("ImpostorRenderer: morphLayers must be >= 0");
    impl_ = std::make_unique<Impl>();
    Impl& r = *impl_;
    r.morphLayers = morphLayers;
    r.context = std::move(context);
    r.context->makeCurrent();
    const GladGLContext& gl = r.context->gl();
    r.program = std::make_unique<ShaderProgram>(*r.context, "ImpostorRenderer shader", kVertexShader, kFragmentShader);
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
    for (GLuint a = 0; a < 4; ++a) gl.VertexAttribDivisor(a, 1);
    gl.BindVertexArray(0);
    gl.UseProgram(r.program->id());
    gl.Uniform1i(r.program->uniformLocation("uCells"), 0);
    gl.UseProgram(0);
}

ImpostorRenderer::~ImpostorRenderer() {
    Impl& r = *impl_;
    try {
        r.context->makeCurrent();
    } catch (...) {
        return;
    }
    const GladGLContext& gl = r.context->gl();
    for (auto& [atlas, g] : r.atlases) gl.DeleteTextures(1, &g.texture);
    gl.DeleteBuffers(1, &r.buffer);
    gl.DeleteVertexArrays(1, &r.vao);
    r.program.reset();
}

const ImpostorRenderStatistics& ImpostorRenderer::statistics() const { return impl_->stats; }

std::size_t ImpostorRenderer::textureBytes() const {
    std::size_t bytes = 0;
    for (const auto& entry : impl_->atlases) {
        const GpuAtlas& g = entry.second;
        bytes += static_cast<std::size_t>(g.layers) * static_cast<std::size_t>(g.cellSize) * static_cast<std::size_t>(g.cellSize) * 4;
    }
    return bytes;
}

void ImpostorRenderer::draw(const Camera& camera, std::span<const ImpostorInstance> instances) {
    Impl& r = *impl_;
    r.stats = {};
    r.context->makeCurrent();
    const GladGLContext& gl = r.context->gl();
    for (auto& [atlas, g] : r.atlases) g.instances.clear(), g.morphedLayer.clear();
    for (const ImpostorInstance& inst : instances) {
        if (!inst.drawable) continue;
        GpuAtlas& g = r.upload(*inst.drawable);
        const ImpostorAtlas& atlas = inst.drawable->atlas();
        const std::uint32_t views = atlas.views().viewCount();
        Instance out{};
        const glm::dvec3 rel = inst.centre - camera.eye();
        out.centreSize[0] = static_cast<float>(rel.x);
        out.centreSize[1] = static_cast<float>(rel.y);
        out.centreSize[2] = static_cast<float>(rel.z);
        out.centreSize[3] = inst.halfSize;
        for (int c = 0; c < 4; ++c) out.tint[c] = inst.tint[c];
        for (std::size_t i = 0; i < 3; ++i) {
            out.weights[i] = inst.weights[i];
            int layer = 0;
            if (inst.weights[i] <= 0.0f) {
                layer = 0;
            } else if (inst.morphed[i] && !g.morphedLayer.count(inst.morphed[i]) &&
                       g.stored + static_cast<int>(g.morphedLayer.size()) >= g.layers) {
                // Pool full: the previous key-frame (always stored next to a dropped one).
                ++r.stats.poolOverflows;
                layer = std::max(g.storedLayer[static_cast<std::size_t>(std::max(inst.keyframe - 1, 0)) * views + inst.views[i]], 0);
            } else if (inst.morphed[i]) {
                auto [it, added] = g.morphedLayer.emplace(inst.morphed[i], g.stored + static_cast<int>(g.morphedLayer.size()));
                if (added) {
                    gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.texture);
                    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
                    gl.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, it->second, atlas.cellSize(), atlas.cellSize(), 1, GL_RGBA,
                                     GL_UNSIGNED_BYTE, inst.morphed[i]->rgba.data());
                    ++r.stats.morphedUploads;
                }
                layer = it->second;
            } else {
                layer = std::max(g.storedLayer[static_cast<std::size_t>(inst.keyframe) * views + inst.views[i]], 0);
            }
            out.layers[i] = static_cast<float>(layer);
        }
        g.instances.push_back(out);
    }
    // The eye at the origin: only the view's rotation goes to the GPU (float precision far away).
    glm::dmat4 rotation = camera.view();
    rotation[3] = glm::dvec4(0, 0, 0, 1);
    const glm::mat4 vrp(camera.projection() * rotation);
    const glm::dmat3 inverse = glm::transpose(glm::dmat3(camera.view()));
    const glm::vec3 right(inverse[0]), up(inverse[1]);
    gl.BindFramebuffer(GL_FRAMEBUFFER, r.context->framebuffer());
    gl.Viewport(0, 0, r.context->width(), r.context->height());
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_BLEND);
    gl.UseProgram(r.program->id());
    gl.UniformMatrix4fv(r.program->uniformLocation("uViewRotationProjection"), 1, GL_FALSE, &vrp[0][0]);
    gl.Uniform3f(r.program->uniformLocation("uRight"), right.x, right.y, right.z);
    gl.Uniform3f(r.program->uniformLocation("uUp"), up.x, up.y, up.z);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindVertexArray(r.vao);
    for (auto& [atlas, g] : r.atlases) {
        if (g.instances.empty()) continue;
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, g.texture);
        gl.BindBuffer(GL_ARRAY_BUFFER, r.buffer);
        gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(g.instances.size() * sizeof(Instance)), g.instances.data(),
                      GL_STREAM_DRAW);
        gl.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(g.instances.size()));
        ++r.stats.drawCalls;
        r.stats.instances += g.instances.size();
    }
    gl.BindVertexArray(0);
    gl.UseProgram(0);
}

}  // namespace throng
