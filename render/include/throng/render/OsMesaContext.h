#pragma once
// A headless GL context: Mesa's OSMesa (llvmpipe) with a core profile, drawing into a framebuffer
// object of the requested size. Needs no display and gives byte-stable images for a Mesa version.

#include "throng/render/GlContext.h"

namespace throng {

/// Off-screen OpenGL core context rendering into an RGBA8 + depth framebuffer object.
class OsMesaContext final : public GlContext {
public:
    /// Creates a core-profile context (3.3 or later) with a `width` x `height` framebuffer and makes
    /// it current. Throws std::invalid_argument for a bad size and std::runtime_error naming the
    /// step that failed (context creation, function loading, framebuffer completeness).
    OsMesaContext(int width, int height);
    ~OsMesaContext() override;

    void makeCurrent() override;
    unsigned framebuffer() const override { return fbo_; }
    int width() const override { return width_; }
    int height() const override { return height_; }
    void resize(int width, int height) override;
    void present() override;
    bool headless() const override { return true; }

private:
    void createFramebuffer();
    void destroyFramebuffer();

    void* context_ = nullptr;        // OSMesaContext, kept opaque so osmesa.h stays private
    unsigned char backing_[4] = {};  // the 1x1 default framebuffer OSMesa requires; we draw to fbo_
    unsigned fbo_ = 0, colour_ = 0, depth_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace throng
