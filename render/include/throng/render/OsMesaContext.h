#pragma once
// A headless GL context: Mesa's OSMesa (llvmpipe) with a core profile, drawing into a framebuffer
// object of the requested size. Needs no display and gives byte-stable images for a Mesa version.

#include "throng/render/HeadlessContext.h"

namespace throng {

/// Off-screen OpenGL core context of OSMesa rendering into an RGBA8 + depth framebuffer object.
class OsMesaContext final : public HeadlessContext {
public:
    /// Creates a core-profile context (3.3 or later) with a `width` x `height` framebuffer and makes
    /// it current. Throws std::invalid_argument for a bad size and std::runtime_error naming the
    /// step that failed (context creation, function loading, framebuffer completeness).
    OsMesaContext(int width, int height);
    ~OsMesaContext() override;

    void makeCurrent() override;

private:
    void* context_ = nullptr;        // OSMesaContext, kept opaque so osmesa.h stays private
    unsigned char backing_[4] = {};  // the 1x1 default framebuffer OSMesa requires; we draw to the FBO
};

}  // namespace throng
