#include "throng/render/OsMesaContext.h"

#include "ColourDepthTarget.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <glad/gl.h>
// osmesa.h includes GL/gl.h, whose declarations glad's header already replaced.
#include <GL/osmesa.h>

namespace throng {
namespace {

OSMesaContext native(void* context) { return static_cast<OSMesaContext>(context); }

std::string hex(unsigned value) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%x", value);
    return text;
}

void checkSize(int width, int height, const char* where) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument(std::string(where) + ": size " + std::to_string(width) + " x " +
                                    std::to_string(height) + " must be positive");
}

}  // namespace

OsMesaContext::OsMesaContext(int width, int height) {
    checkSize(width, height, "OsMesaContext");
    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                              OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context_)
        throw std::runtime_error("OsMesaContext: OSMesaCreateContextAttribs failed to create an OpenGL 3.3 "
                                 "core-profile context (is Mesa's llvmpipe available?)");
    try {
        makeCurrent();
        loadFunctions(&OSMesaGetProcAddress, "OSMesa (headless)");
        width_ = width;
        height_ = height;
        createFramebuffer();
    } catch (...) {
        destroyFramebuffer();
        OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
        OSMesaDestroyContext(native(context_));
        throw;
    }
}

OsMesaContext::~OsMesaContext() {
    // GL objects can only be deleted with the context current; if that fails, destroying the
    // context frees them anyway.
    if (OSMesaGetCurrentContext() == native(context_) ||
        OSMesaMakeCurrent(native(context_), backing_, GL_UNSIGNED_BYTE, 1, 1))
        destroyFramebuffer();
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(native(context_));
}

void OsMesaContext::makeCurrent() {
    if (OSMesaGetCurrentContext() == native(context_)) return;
    if (!OSMesaMakeCurrent(native(context_), backing_, GL_UNSIGNED_BYTE, 1, 1))
        throw std::runtime_error("OsMesaContext: OSMesaMakeCurrent failed");
}

void OsMesaContext::createFramebuffer() {
    const GladGLContext& g = gl();
    GLint maxSize = 0, maxViewport[2] = {0, 0};
    g.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    g.GetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int limitW = std::min(maxSize, maxViewport[0]), limitH = std::min(maxSize, maxViewport[1]);
    if (width_ > limitW || height_ > limitH)
        throw std::invalid_argument("OsMesaContext: size " + std::to_string(width_) + " x " + std::to_string(height_) +
                                    " exceeds the implementation's limit of " + std::to_string(limitW) + " x " +
                                    std::to_string(limitH));
    detail::ColourDepthTarget target;
    const GLenum status = detail::createColourDepthTarget(g, width_, height_, target);
    fbo_ = target.fbo, colour_ = target.colour, depth_ = target.depth;
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("OsMesaContext: the " + std::to_string(width_) + " x " + std::to_string(height_) +
                                 " framebuffer object is incomplete (status " + hex(status) + ")");
    if (g.GetError() != GL_NO_ERROR)
        throw std::runtime_error("OsMesaContext: creating the " + std::to_string(width_) + " x " +
                                 std::to_string(height_) + " framebuffer raised a GL error (out of memory?)");
}

void OsMesaContext::destroyFramebuffer() {
    if (!gl().DeleteFramebuffers) return;  // functions never loaded
    detail::ColourDepthTarget target{fbo_, colour_, depth_};
    detail::deleteColourDepthTarget(gl(), target);
    fbo_ = colour_ = depth_ = 0;
}

void OsMesaContext::resize(int width, int height) {
    checkSize(width, height, "OsMesaContext::resize");
    if (width == width_ && height == height_) return;
    makeCurrent();
    const int oldW = width_, oldH = height_;
    destroyFramebuffer();
    width_ = width;
    height_ = height;
    try {
        createFramebuffer();
    } catch (...) {
        destroyFramebuffer();  // restore the previous, valid framebuffer before reporting
        width_ = oldW;
        height_ = oldH;
        createFramebuffer();
        throw;
    }
}

void OsMesaContext::present() {
    makeCurrent();
    gl().Finish();  // llvmpipe rasterises on worker threads: the frame is done only after this
}

}  // namespace throng
