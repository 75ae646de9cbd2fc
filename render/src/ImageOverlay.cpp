#include "throng/render/ImageOverlay.h"

#include <glad/gl.h>

#include <stdexcept>
#include <string>

#include "OverlayState.h"
#include "throng/render/GlContext.h"
#include "throng/render/ShaderProgram.h"

namespace throng {
namespace {

constexpr const char* kVertex = R"(#version 330 core
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 texcoord;
uniform vec2 viewport;
out vec2 vTexcoord;
void main() {
    vTexcoord = texcoord;
    gl_Position = vec4(position.x / viewport.x * 2.0 - 1.0, 1.0 - position.y / viewport.y * 2.0, 0.0, 1.0);
})";

constexpr const char* kFragment = R"(#version 330 core
in vec2 vTexcoord;
uniform sampler2D image;
out vec4 fragColour;
void main() { fragColour = texture(image, vTexcoord); })";

}  // namespace

ImageOverlay::ImageOverlay(GlContext& context) : context_(context) {
    context_.makeCurrent();
    program_ = std::make_unique<ShaderProgram>(context_, "image overlay", kVertex, kFragment);
    const GladGLContext& gl = context_.gl();
    gl.GenVertexArrays(1, &vao_);
    gl.GenBuffers(1, &vbo_);
    gl.GenTextures(1, &texture_);
    gl.BindVertexArray(vao_);
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo_);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
    gl.EnableVertexAttribArray(1);
    gl.VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float), reinterpret_cast<void*>(2 * sizeof(float)));
    gl.BindVertexArray(0);
}

ImageOverlay::~ImageOverlay() {
    context_.makeCurrent();
    const GladGLContext& gl = context_.gl();
    gl.DeleteTextures(1, &texture_);
    gl.DeleteBuffers(1, &vbo_);
    gl.DeleteVertexArrays(1, &vao_);
}

void ImageOverlay::draw(const Image& image, int x, int y, int width, int height) {
    if (image.width <= 0 || image.height <= 0 || image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4)
        throw std::invalid_argument("ImageOverlay::draw: image '" + image.name + "' has " + std::to_string(image.rgba.size()) +
                                    " bytes for " + std::to_string(image.width) + " x " + std::to_string(image.height) + " pixels");
    context_.makeCurrent();
    const GladGLContext& gl = context_.gl();
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, texture_);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    const float x0 = float(x), y0 = float(y), x1 = float(x + width), y1 = float(y + height);
    // Texture row 0 is the image's top row.
    const float quad[6][4] = {{x0, y0, 0, 0}, {x1, y0, 1, 0}, {x1, y1, 1, 1}, {x0, y0, 0, 0}, {x1, y1, 1, 1}, {x0, y1, 0, 1}};

    const detail::OverlayState state(context_);
    gl.UseProgram(program_->id());
    gl.Uniform2f(program_->uniformLocation("viewport"), float(context_.width()), float(context_.height()));
    gl.Uniform1i(program_->uniformLocation("image"), 0);
    gl.BindVertexArray(vao_);
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo_);
    gl.BufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STREAM_DRAW);
    gl.DrawArrays(GL_TRIANGLES, 0, 6);
}

}  // namespace throng
