#pragma once
// Private to throng::render: a framebuffer object with an RGBA8 colour and a 24-bit depth
// renderbuffer, as the headless context's frame and the scaled frame (ScaledFrame) both need.

#include <glad/gl.h>

namespace throng::detail {

/// GL names of a colour-and-depth framebuffer (0: none).
struct ColourDepthTarget {
    GLuint fbo = 0, colour = 0, depth = 0;
};

/// Creates a `width` x `height` target into `out` and leaves its framebuffer bound; returns
/// glCheckFramebufferStatus (GL_FRAMEBUFFER_COMPLETE when usable). The caller owns the names.
inline GLenum createColourDepthTarget(const GladGLContext& g, int width, int height, ColourDepthTarget& out) {
    g.GenFramebuffers(1, &out.fbo);
    g.GenRenderbuffers(1, &out.colour);
    g.GenRenderbuffers(1, &out.depth);
    g.BindRenderbuffer(GL_RENDERBUFFER, out.colour);
    g.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    g.BindRenderbuffer(GL_RENDERBUFFER, out.depth);
    g.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    g.BindRenderbuffer(GL_RENDERBUFFER, 0);
    g.BindFramebuffer(GL_FRAMEBUFFER, out.fbo);
    g.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, out.colour);
    g.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, out.depth);
    return g.CheckFramebufferStatus(GL_FRAMEBUFFER);
}

/// Deletes what createColourDepthTarget made and zeroes the names (the context current).
inline void deleteColourDepthTarget(const GladGLContext& g, ColourDepthTarget& t) {
    if (t.fbo) g.DeleteFramebuffers(1, &t.fbo);
    if (t.colour) g.DeleteRenderbuffers(1, &t.colour);
    if (t.depth) g.DeleteRenderbuffers(1, &t.depth);
    t = ColourDepthTarget{};
}

}  // namespace throng::detail
