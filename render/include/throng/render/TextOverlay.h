#pragma once
// Text drawn over a frame (on-screen statistics and key help in the town's window), with the
// stb_easy_font vector font: no font file, no texture.

#include <memory>
#include <string>

#include <glm/vec4.hpp>

namespace throng {

class GlContext;
class ShaderProgram;

/// Draws lines of text onto the current framebuffer of a context.
class TextOverlay {
public:
    /// An overlay for `context` (made current while drawing).
    explicit TextOverlay(GlContext& context);
    ~TextOverlay();
    TextOverlay(const TextOverlay&) = delete;
    TextOverlay& operator=(const TextOverlay&) = delete;

    /// Draws `text` (lines separated by '\n') with its top-left corner at pixel (x, y) from the
    /// framebuffer's top-left, at `scale` times the font's 6 x 12 pixels, over a translucent panel.
    void draw(const std::string& text, int x, int y, float scale = 2.0f, const glm::vec4& color = glm::vec4(1.0f));

private:
    GlContext& context_;
    std::unique_ptr<ShaderProgram> program_;
    unsigned vao_ = 0, vbo_ = 0;
};

}  // namespace throng
