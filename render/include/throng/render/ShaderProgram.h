#pragma once
// A linked GLSL program. Compile and link failures throw with the driver's log and the program's
// name, so a broken shader is reported rather than drawn as nothing.

#include <span>
#include <string>

namespace throng {

class GlContext;

/// A vertex (+ optional fragment) program in one GlContext, deleted with the object.
class ShaderProgram {
public:
    /// Compiles and links in `context` (made current). `fragmentSource` may be empty (a transform
    /// feedback program); `feedbackVaryings` are captured interleaved. Throws std::runtime_error
    /// "<name>: the vertex shader failed to compile: <log>" (or fragment shader, or link).
    ShaderProgram(GlContext& context, std::string name, const std::string& vertexSource,
                  const std::string& fragmentSource, std::span<const char* const> feedbackVaryings = {});
    ~ShaderProgram();
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    /// GL name of the program.
    unsigned id() const { return id_; }
    /// Name given at construction.
    const std::string& name() const { return name_; }
    /// Location of uniform `uniform` (-1 if the program does not use it).
    int uniformLocation(const char* uniform) const;

private:
    GlContext& context_;
    std::string name_;
    unsigned id_ = 0;
};

}  // namespace throng
