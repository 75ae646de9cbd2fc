#pragma once
// Internal to render: the GL state every screen overlay (text, images) draws in, set for the
// overlay's lifetime and put back after: the context's framebuffer and viewport, alpha blending,
// no depth test, no face culling (2D quads in whatever winding).

#include <glad/gl.h>

#include "throng/render/GlContext.h"

namespace throng::detail {

/// Sets the overlay state on construction, restores the 3D state on destruction.
class OverlayState {
public:
    explicit OverlayState(GlContext& context) : gl_(context.gl()) {
        context.makeCurrent();
        gl_.BindFramebuffer(GL_FRAMEBUFFER, context.framebuffer());
        gl_.Viewport(0, 0, context.width(), context.height());
        culling_ = gl_.IsEnabled(GL_CULL_FACE);
        gl_.Disable(GL_CULL_FACE);
        gl_.Disable(GL_DEPTH_TEST);
        gl_.Enable(GL_BLEND);
        gl_.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    }
    ~OverlayState() {
        gl_.BindVertexArray(0);
        gl_.Disable(GL_BLEND);
        gl_.Enable(GL_DEPTH_TEST);
        if (culling_) gl_.Enable(GL_CULL_FACE);
    }
    OverlayState(const OverlayState&) = delete;
    OverlayState& operator=(const OverlayState&) = delete;

private:
    const GladGLContext& gl_;
    GLboolean culling_ = GL_FALSE;
};

}  // namespace throng::detail
