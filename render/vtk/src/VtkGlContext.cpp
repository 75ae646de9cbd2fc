#include "VtkGlContext.h"

#include <stdexcept>
#include <string>

#include <GL/glx.h>

namespace throng::vtk {

namespace {

// glXGetProcAddressARB takes unsigned chars; the loader type takes chars.
void (*loadGlx(const char* name))() { return glXGetProcAddressARB(reinterpret_cast<const GLubyte*>(name)); }

}  // namespace

VtkGlContext::VtkGlContext() {
    if (!glXGetCurrentContext()) throw std::runtime_error("CrowdProp: no current GLX context to draw into (Throng drawing needs VTK's X window)");
    loadFunctions(&loadGlx, "VTK (GLX)");
}

void VtkGlContext::setTarget(unsigned framebuffer, int x, int y, int width, int height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("CrowdProp: the renderer's viewport is " + std::to_string(width) + " x " + std::to_string(height) + " pixels");
    framebuffer_ = framebuffer;
    x_ = x, y_ = y, width_ = width, height_ = height;
}

void VtkGlContext::resize(int, int) { throw std::logic_error("VtkGlContext::resize: the viewport is VTK's renderer's (setTarget)"); }

}  // namespace throng::vtk
