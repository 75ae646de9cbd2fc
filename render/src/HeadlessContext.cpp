#include "throng/render/HeadlessContext.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "ColourDepthTarget.h"

namespace throng {
namespace {

std::string hex(unsigned value) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%x", value);
    return text;
}

}  // namespace

void HeadlessContext::checkSize(int width, int height) const {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument(kind_ + ": size " + std::to_string(width) + " x " + std::to_string(height) + " must be positive");
}

void HeadlessContext::createFramebuffer(int width, int height) {
    const GladGLContext& g = gl();
    GLint maxSize = 0, maxViewport[2] = {0, 0};
    g.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    g.GetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int limitW = std::min(maxSize, maxViewport[0]), limitH = std::min(maxSize, maxViewport[1]);
    if (width > limitW || height > limitH)
        throw std::invalid_argument(kind_ + ": size " + std::to_string(width) + " x " + std::to_string(height) +
                                    " exceeds the implementation's limit of " + std::to_string(limitW) + " x " + std::to_string(limitH));
    detail::ColourDepthTarget target;
    const GLenum status = detail::createColourDepthTarget(g, width, height, target);
    fbo_ = target.fbo, colour_ = target.colour, depth_ = target.depth;
    width_ = width, height_ = height;
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error(kind_ + ": the " + std::to_string(width) + " x " + std::to_string(height) +
                                 " framebuffer object is incomplete (status " + hex(status) + ")");
    if (g.GetError() != GL_NO_ERROR)
        throw std::runtime_error(kind_ + ": creating the " + std::to_string(width) + " x " + std::to_string(height) +
                                 " framebuffer raised a GL error (out of memory?)");
}

void HeadlessContext::destroyFramebuffer() {
    if (!gl().DeleteFramebuffers) return;  // functions never loaded
    detail::ColourDepthTarget target{fbo_, colour_, depth_};
    detail::deleteColourDepthTarget(gl(), target);
    fbo_ = colour_ = depth_ = 0;
}

void HeadlessContext::resize(int width, int height) {
    checkSize(width, height);
    if (width == width_ && height == height_) return;
    makeCurrent();
    const int oldW = width_, oldH = height_;
    destroyFramebuffer();
    try {
        createFramebuffer(width, height);
    } catch (...) {
        destroyFramebuffer();  // restore the previous, valid framebuffer before reporting
        createFramebuffer(oldW, oldH);
        throw;
    }
}

void HeadlessContext::present() {
    makeCurrent();
    gl().Finish();
}

}  // namespace throng
