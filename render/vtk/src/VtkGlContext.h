#pragma once
// VTK's OpenGL context seen as a Throng GlContext, so that Throng's renderer can draw into a frame
// VTK is rendering (CrowdProp): the function table is loaded through GLX from the context current
// when it is made, the framebuffer and viewport are those VTK has bound for the renderer being
// drawn, and making current or presenting is left to VTK. Private to throng::vtk.

#include "throng/render/GlContext.h"

namespace throng::vtk {

/// The GL context VTK has made current, with the framebuffer area VTK draws a renderer into.
class VtkGlContext final : public GlContext {
public:
    /// Loads the function table from the current context. Throws std::runtime_error when no context
    /// is current or its OpenGL is older than 3.3.
    VtkGlContext();
    /// The framebuffer object and viewport of the renderer about to be drawn (in pixels).
    void setTarget(unsigned framebuffer, int x, int y, int width, int height);

    void makeCurrent() override {}  // VTK made its context current before it asked the prop to render
    unsigned framebuffer() const override { return framebuffer_; }
    int width() const override { return width_; }
    int height() const override { return height_; }
    int originX() const override { return x_; }
    int originY() const override { return y_; }
    /// The viewport follows VTK's renderer (setTarget); throws std::logic_error.
    void resize(int width, int height) override;
    void present() override {}  // VTK swaps or reads the frame
    bool headless() const override { return true; }

private:
    unsigned framebuffer_ = 0;
    int x_ = 0, y_ = 0, width_ = 1, height_ = 1;
};

}  // namespace throng::vtk
