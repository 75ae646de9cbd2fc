#include "throng/render/GpuSkinner.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include <glad/gl.h>

#include "GlMesh.h"
#include "Shaders.h"
#include "throng/render/GlContext.h"
#include "throng/render/ShaderProgram.h"

namespace throng {
namespace {

[[noreturn]] void fail(const MeshData& mesh, const std::string& what) {
    throw std::invalid_argument("GpuSkinner::skin: mesh '" + mesh.name + "': " + what);
}

}  // namespace

struct GpuSkinner::Impl {
    std::shared_ptr<GlContext> context;  // first member: destroyed last
    std::unique_ptr<ShaderProgram> programs[2];  // 4 and 8 influences
    GLuint paletteBuffer = 0, paletteTexture = 0, feedbackBuffer = 0;
};

GpuSkinner::GpuSkinner(std::shared_ptr<GlContext> context) {
    if (!context) throw std::invalid_argument("GpuSkinner: argument 'context' is null");
    impl_ = std::make_unique<Impl>();
    Impl& s = *impl_;
    s.context = std::move(context);
    s.context->makeCurrent();
    const GladGLContext& gl = s.context->gl();
    const char* const varyings[] = {"tfPosition", "tfNormal"};
    for (int k = 0; k < 2; ++k) {
        const int influences = k == 0 ? 4 : 8;
        s.programs[k] = std::make_unique<ShaderProgram>(
            *s.context, "GpuSkinner shader (" + std::to_string(influences) + " joint influences)",
            detail::vertexShaderSource(influences, true), std::string(), varyings);
        gl.UseProgram(s.programs[k]->id());
        gl.Uniform1i(s.programs[k]->uniformLocation("uPalette"), detail::kPaletteUnit);
    }
    gl.UseProgram(0);
    gl.GenBuffers(1, &s.paletteBuffer);
    gl.GenBuffers(1, &s.feedbackBuffer);
    gl.GenTextures(1, &s.paletteTexture);
    gl.BindBuffer(GL_TEXTURE_BUFFER, s.paletteBuffer);
    gl.BufferData(GL_TEXTURE_BUFFER, sizeof(glm::mat4), nullptr, GL_STREAM_DRAW);
    gl.BindTexture(GL_TEXTURE_BUFFER, s.paletteTexture);
    gl.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, s.paletteBuffer);
}

GpuSkinner::~GpuSkinner() {
    Impl& s = *impl_;
    try {
        s.context->makeCurrent();
    } catch (...) {
        return;
    }
    const GladGLContext& gl = s.context->gl();
    const GLuint buffers[] = {s.paletteBuffer, s.feedbackBuffer};
    gl.DeleteBuffers(2, buffers);
    gl.DeleteTextures(1, &s.paletteTexture);
}

void GpuSkinner::skin(const MeshData& mesh, std::span<const glm::mat4> palette, std::span<glm::vec3> positions,
                      std::span<glm::vec3> normals) {
    if (!mesh.skinned()) fail(mesh, "is not skinned (it has no joints0/weights0)");
    mesh.validate();
    const std::size_t n = mesh.vertexCount();
    if (positions.size() != n)
        fail(mesh, "output 'positions' holds " + std::to_string(positions.size()) + " vertices, the mesh has " +
                       std::to_string(n));
    if (!normals.empty() && normals.size() != n)
        fail(mesh, "output 'normals' holds " + std::to_string(normals.size()) + " vertices, the mesh has " +
                       std::to_string(n));
    Impl& s = *impl_;
    s.context->makeCurrent();
    const GladGLContext& gl = s.context->gl();
    detail::GlMesh m = detail::uploadMesh(gl, mesh);
    struct Cleanup {
        const GladGLContext& gl;
        detail::GlMesh& m;
        ~Cleanup() { detail::destroyMesh(gl, m); }
    } cleanup{gl, m};
    if (palette.size() < m.requiredPalette)
        fail(mesh, "a joint index needs a palette of " + std::to_string(m.requiredPalette) +
                       " matrices, the palette has " + std::to_string(palette.size()));

    gl.BindBuffer(GL_TEXTURE_BUFFER, s.paletteBuffer);
    gl.BufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(std::max<std::size_t>(palette.size(), 1) * sizeof(glm::mat4)),
                  nullptr, GL_STREAM_DRAW);
    if (!palette.empty())
        gl.BufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(palette.size_bytes()), palette.data());
    const std::size_t bytes = n * 2 * sizeof(glm::vec3);
    gl.BindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, s.feedbackBuffer);
    gl.BufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_STREAM_READ);
    gl.BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, s.feedbackBuffer);

    gl.UseProgram(s.programs[m.influences == 8 ? 1 : 0]->id());
    gl.ActiveTexture(GL_TEXTURE0 + detail::kPaletteUnit);
    gl.BindTexture(GL_TEXTURE_BUFFER, s.paletteTexture);
    gl.BindVertexArray(m.vao);
    gl.Enable(GL_RASTERIZER_DISCARD);
    gl.BeginTransformFeedback(GL_POINTS);
    gl.DrawArrays(GL_POINTS, 0, static_cast<GLsizei>(n));
    gl.EndTransformFeedback();
    gl.Disable(GL_RASTERIZER_DISCARD);
    gl.BindVertexArray(0);
    gl.UseProgram(0);

    std::vector<glm::vec3> captured(2 * n);  // interleaved position, normal
    gl.GetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, static_cast<GLsizeiptr>(bytes), captured.data());
    gl.BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    if (gl.GetError() != GL_NO_ERROR) throw std::runtime_error("GpuSkinner::skin: mesh '" + mesh.name + "': a GL error occurred");
    const bool doNormals = !normals.empty() && !mesh.normals.empty();
    for (std::size_t v = 0; v < n; ++v) {
        positions[v] = captured[2 * v];
        if (doNormals) normals[v] = captured[2 * v + 1];
    }
}

}  // namespace throng
