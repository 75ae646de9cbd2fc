#pragma once
// What every headless GL context shares: it draws into a framebuffer object of its own (RGBA8 and
// depth), resized on request, and a frame is complete once GL has finished it. OsMesaContext and
// EglContext differ only in how the context itself is made current.

#include <string>

#include "throng/render/GlContext.h"

namespace throng {

/// An off-screen GL context drawing into its own colour-and-depth framebuffer object.
class HeadlessContext : public GlContext {
public:
    unsigned framebuffer() const override { return fbo_; }
    int width() const override { return width_; }
    int height() const override { return height_; }
    /// Remakes the framebuffer at the new size; on failure the previous one is restored and the
    /// error thrown (std::invalid_argument beyond the implementation's limits).
    void resize(int width, int height) override;
    /// Waits until the frame is complete (glFinish: software rasterisers draw on worker threads, a
    /// GPU asynchronously).
    void present() override;
    bool headless() const override { return true; }

protected:
    /// `kind` names the context in errors ("OsMesaContext", "EglContext").
    explicit HeadlessContext(std::string kind) : kind_(std::move(kind)) {}
    /// Throws std::invalid_argument unless both sizes are positive (before anything is made).
    void checkSize(int width, int height) const;
    /// Creates the `width` x `height` framebuffer (functions loaded, context current). Throws
    /// std::invalid_argument beyond the implementation's limits, std::runtime_error when incomplete.
    void createFramebuffer(int width, int height);
    /// Deletes the framebuffer (context current; nothing when the functions were never loaded).
    void destroyFramebuffer();

private:
    std::string kind_;
    unsigned fbo_ = 0, colour_ = 0, depth_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace throng
