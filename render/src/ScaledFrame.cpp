#include "throng/render/ScaledFrame.h"

#include "throng/render/GlContext.h"

#include "ColourDepthTarget.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace throng {

ScaledFrame::ScaledFrame(GlContext& context) : context_(context) {}

ScaledFrame::~ScaledFrame() {
    if (inFrame_) context_.redirectDrawing(std::nullopt);
    release();
}

void ScaledFrame::release() {
    if (!fbo_) return;
    context_.makeCurrent();
    detail::ColourDepthTarget target{fbo_, colour_, depth_};
    detail::deleteColourDepthTarget(context_.gl(), target);
    fbo_ = colour_ = depth_ = 0;
}

void ScaledFrame::begin(float scale) {
    if (!(scale > 0.0f && scale < 1.0f))
        throw std::invalid_argument("ScaledFrame::begin: scale must be above 0 and below 1, not " + std::to_string(scale));
    if (inFrame_) throw std::logic_error("ScaledFrame::begin: a frame is already begun");
    const GlContext::DrawTarget full = context_.drawTarget();
    const int w = std::max(1, int(std::lround(double(full.width) * scale)));
    const int h = std::max(1, int(std::lround(double(full.height) * scale)));
    context_.makeCurrent();
    const GladGLContext& gl = context_.gl();
    if (w != width_ || h != height_ || !fbo_) {  // (re)allocated only when the size changes
        release();
        detail::ColourDepthTarget target;
        const GLenum status = detail::createColourDepthTarget(gl, w, h, target);
        fbo_ = target.fbo, colour_ = target.colour, depth_ = target.depth;
        gl.BindFramebuffer(GL_FRAMEBUFFER, full.framebuffer);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            release();
            throw std::runtime_error("ScaledFrame: the GL refused a " + std::to_string(w) + "x" + std::to_string(h) +
                                     " colour and depth target (status " + std::to_string(status) + ")");
        }
        width_ = w, height_ = h;
    }
    context_.redirectDrawing(GlContext::DrawTarget{fbo_, 0, 0, w, h});
    inFrame_ = true;
}

void ScaledFrame::end() {
    if (!inFrame_) throw std::logic_error("ScaledFrame::end: no frame was begun");
    context_.redirectDrawing(std::nullopt);
    inFrame_ = false;
    const GlContext::DrawTarget full = context_.drawTarget();
    context_.makeCurrent();
    const GladGLContext& gl = context_.gl();
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, full.framebuffer);
    gl.Disable(GL_SCISSOR_TEST);
    gl.BlitFramebuffer(0, 0, width_, height_, full.x, full.y, full.x + full.width, full.y + full.height,
                       GL_COLOR_BUFFER_BIT, GL_LINEAR);
    gl.BindFramebuffer(GL_FRAMEBUFFER, full.framebuffer);
    gl.Viewport(full.x, full.y, full.width, full.height);
}

}  // namespace throng
