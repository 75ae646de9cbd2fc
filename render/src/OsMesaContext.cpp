#include "throng/render/OsMesaContext.h"

#include <stdexcept>
#include <string>

#include <glad/gl.h>
// osmesa.h includes GL/gl.h, whose declarations glad's header already replaced.
#include <GL/osmesa.h>

namespace throng {
namespace {

OSMesaContext native(void* context) { return static_cast<OSMesaContext>(context); }

}  // namespace

OsMesaContext::OsMesaContext(int width, int height) : HeadlessContext("OsMesaContext") {
    checkSize(width, height);
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
        createFramebuffer(width, height);
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

}  // namespace throng
