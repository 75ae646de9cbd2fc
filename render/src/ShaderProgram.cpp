#include "throng/render/ShaderProgram.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include <glad/gl.h>

#include "throng/render/GlContext.h"

namespace throng {
namespace {

std::string shaderLog(const GladGLContext& gl, GLuint shader) {
    GLint length = 0;
    gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    gl.GetShaderInfoLog(shader, length, nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    return log.empty() ? "(no log)" : log;
}

std::string programLog(const GladGLContext& gl, GLuint program) {
    GLint length = 0;
    gl.GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    gl.GetProgramInfoLog(program, length, nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    return log.empty() ? "(no log)" : log;
}

GLuint compile(const GladGLContext& gl, GLenum stage, const std::string& source, const std::string& name) {
    const GLuint shader = gl.CreateShader(stage);
    const char* text = source.c_str();
    gl.ShaderSource(shader, 1, &text, nullptr);
    gl.CompileShader(shader);
    GLint ok = GL_FALSE;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = shaderLog(gl, shader);
        gl.DeleteShader(shader);
        throw std::runtime_error(name + ": the " + (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                                 " shader failed to compile: " + log);
    }
    return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(GlContext& context, std::string name, const std::string& vertexSource,
                             const std::string& fragmentSource, std::span<const char* const> feedbackVaryings)
    : context_(context), name_(std::move(name)) {
    context_.makeCurrent();
    const GladGLContext& gl = context_.gl();
    const GLuint vs = compile(gl, GL_VERTEX_SHADER, vertexSource, name_);
    GLuint fs = 0;
    if (!fragmentSource.empty()) {
        try {
            fs = compile(gl, GL_FRAGMENT_SHADER, fragmentSource, name_);
        } catch (...) {
            gl.DeleteShader(vs);
            throw;
        }
    }
    id_ = gl.CreateProgram();
    gl.AttachShader(id_, vs);
    if (fs) gl.AttachShader(id_, fs);
    if (!feedbackVaryings.empty())
        gl.TransformFeedbackVaryings(id_, static_cast<GLsizei>(feedbackVaryings.size()), feedbackVaryings.data(),
                                     GL_INTERLEAVED_ATTRIBS);
    gl.LinkProgram(id_);
    gl.DeleteShader(vs);  // flagged for deletion; freed with the program
    if (fs) gl.DeleteShader(fs);
    GLint ok = GL_FALSE;
    gl.GetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = programLog(gl, id_);
        gl.DeleteProgram(id_);
        throw std::runtime_error(name_ + ": the program failed to link: " + log);
    }
}

ShaderProgram::~ShaderProgram() {
    try {
        context_.makeCurrent();
    } catch (...) {
        return;  // the context is unusable; destroying it frees the program
    }
    context_.gl().DeleteProgram(id_);
}

int ShaderProgram::uniformLocation(const char* uniform) const {
    return context_.gl().GetUniformLocation(id_, uniform);
}

}  // namespace throng
