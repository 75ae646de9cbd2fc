#pragma once
// Dynamic resolution: a frame drawn off screen at a fraction of the context's size, then scaled up
// into the context's framebuffer. A software GL pays for every pixel shaded, so half the width and
// height costs about a quarter of the fill; the error it costs is measured like any approximation.

namespace throng {

class GlContext;

/// An offscreen colour and depth target at `scale` x the context's size, and its scaling up.
class ScaledFrame {
public:
    /// A target for frames drawn into `context` (made current when the target is used).
    explicit ScaledFrame(GlContext& context);
    ~ScaledFrame();
    ScaledFrame(const ScaledFrame&) = delete;
    ScaledFrame& operator=(const ScaledFrame&) = delete;

    /// Sends the context's passes to the offscreen target, `scale` x the context's width and height
    /// (at least one pixel each). Throws std::invalid_argument unless 0 < scale < 1, or
    /// std::logic_error when a frame is already begun.
    void begin(float scale);
    /// Scales the frame up into the context's own framebuffer (bilinear) and gives drawing back to it.
    /// Throws std::logic_error when no frame was begun.
    void end();
    /// Size of the offscreen target of the last begin() (0 before).
    int width() const { return width_; }
    /// See width().
    int height() const { return height_; }

private:
    void release();
    GlContext& context_;
    unsigned fbo_ = 0, colour_ = 0, depth_ = 0;
    int width_ = 0, height_ = 0;
    bool inFrame_ = false;
};

}  // namespace throng
