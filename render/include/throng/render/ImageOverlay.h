#pragma once
// An image drawn over a frame (the town window's view of the occlusion buffer): an RGBA8 image
// uploaded to a texture and drawn as one quad at a pixel rectangle, blended by its alpha.

#include "throng/scenegraph/Image.h"

#include <memory>

namespace throng {

class GlContext;
class ShaderProgram;

/// Draws images onto the current framebuffer of a context.
class ImageOverlay {
public:
    /// An overlay for `context` (made current while drawing).
    explicit ImageOverlay(GlContext& context);
    ~ImageOverlay();
    ImageOverlay(const ImageOverlay&) = delete;
    ImageOverlay& operator=(const ImageOverlay&) = delete;

    /// Draws `image` (RGBA8, top row first) with its top-left corner at pixel (x, y) from the
    /// framebuffer's top-left, `width` x `height` pixels. Throws std::invalid_argument for an image
    /// whose pixel count does not match its size.
    void draw(const Image& image, int x, int y, int width, int height);

private:
    GlContext& context_;
    std::unique_ptr<ShaderProgram> program_;
    unsigned vao_ = 0, vbo_ = 0, texture_ = 0;
};

}  // namespace throng
