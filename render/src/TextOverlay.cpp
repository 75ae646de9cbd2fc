#include "throng/render/TextOverlay.h"

#include <glad/gl.h>

#include <algorithm>
#include <vector>

#include "OverlayState.h"
#include "throng/render/GlContext.h"
#include "throng/render/ShaderProgram.h"

#include <stb/stb_easy_font.h>

namespace throng {
namespace {

constexpr const char* kVertex = R"(#version 330 core
layout(location = 0) in vec2 position;
layout(location = 1) in vec4 colour;
uniform vec2 viewport;
out vec4 vColour;
void main() {
    vColour = colour;
    gl_Position = vec4(position.x / viewport.x * 2.0 - 1.0, 1.0 - position.y / viewport.y * 2.0, 0.0, 1.0);
})";

constexpr const char* kFragment = R"(#version 330 core
in vec4 vColour;
out vec4 fragColour;
void main() { fragColour = vColour; })";

struct Vertex {
    float x, y;
    float r, g, b, a;
};

void quad(std::vector<Vertex>& out, float x0, float y0, float x1, float y1, const glm::vec4& c) {
    const Vertex v[4] = {{x0, y0, c.r, c.g, c.b, c.a}, {x1, y0, c.r, c.g, c.b, c.a}, {x1, y1, c.r, c.g, c.b, c.a}, {x0, y1, c.r, c.g, c.b, c.a}};
    for (int i : {0, 1, 2, 0, 2, 3}) out.push_back(v[i]);
}

}  // namespace

TextOverlay::TextOverlay(GlContext& context) : context_(context) {
    context_.makeCurrent();
    program_ = std::make_unique<ShaderProgram>(context_, "text overlay", kVertex, kFragment);
    const GladGLContext& gl = context_.gl();
    gl.GenVertexArrays(1, &vao_);
    gl.GenBuffers(1, &vbo_);
    gl.BindVertexArray(vao_);
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo_);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex), nullptr);
    gl.EnableVertexAttribArray(1);
    gl.VertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(2 * sizeof(float)));
    gl.BindVertexArray(0);
}

TextOverlay::~TextOverlay() {
    context_.makeCurrent();
    const GladGLContext& gl = context_.gl();
    gl.DeleteBuffers(1, &vbo_);
    gl.DeleteVertexArrays(1, &vao_);
}

void TextOverlay::draw(const std::string& text, int x, int y, float scale, const glm::vec4& color) {
    if (text.empty()) return;
    // stb_easy_font writes quads of 4 vertices (x, y, z, colour) into a buffer it is given.
    static thread_local std::vector<char> buffer(1 << 20);
    std::vector<Vertex> tris;
    float width = 0.0f, lines = 0.0f;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        std::string line = text.substr(start, end - start);
        width = std::max(width, float(stb_easy_font_width(line.data())));
        const int quads = stb_easy_font_print(0.0f, lines * 12.0f, line.data(), nullptr, buffer.data(), int(buffer.size()));
        const auto* v = reinterpret_cast<const float*>(buffer.data());
        for (int q = 0; q < quads; ++q) {
            const float* p = v + q * 16;  // 4 vertices of 4 floats (x, y, z, packed colour)
            quad(tris, x + p[0] * scale, y + p[1] * scale, x + p[8] * scale, y + p[9] * scale, color);
        }
        lines += 1.0f;
        start = end + 1;
    }
    std::vector<Vertex> all;
    quad(all, float(x) - 6, float(y) - 6, x + width * scale + 6, y + lines * 12.0f * scale + 2, glm::vec4(0, 0, 0, 0.55f));
    all.insert(all.end(), tris.begin(), tris.end());

    const detail::OverlayState state(context_);
    const GladGLContext& gl = context_.gl();
    gl.UseProgram(program_->id());
    gl.Uniform2f(program_->uniformLocation("viewport"), float(context_.width()), float(context_.height()));
    gl.BindVertexArray(vao_);
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo_);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(all.size() * sizeof(Vertex)), all.data(), GL_STREAM_DRAW);
    gl.DrawArrays(GL_TRIANGLES, 0, GLsizei(all.size()));
}

}  // namespace throng
