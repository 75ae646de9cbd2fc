#pragma once
// An OpenGL 3.3+ core context and the framebuffer it draws into. The renderer is written once
// against this interface; OsMesaContext and EglContext (headless) and GlfwWindowContext (window)
// implement it.

#include <memory>
#include <optional>
#include <string>

// The glad2 function table of one context (generated at build time, kept private to throng::render).
struct GladGLContext;

namespace throng {

/// A current-able GL context with its own function table and a target framebuffer.
class GlContext {
public:
    /// A function the loader calls to find one GL entry point by name.
    using ProcLoader = void (*(*)(const char* name))();

    virtual ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    /// Makes this context current on the calling thread (cheap when it already is).
    virtual void makeCurrent() = 0;
    /// Name of the framebuffer object to draw into (0 = the window's default framebuffer).
    virtual unsigned framebuffer() const = 0;
    /// Width of that framebuffer in pixels.
    virtual int width() const = 0;
    /// Height of that framebuffer in pixels.
    virtual int height() const = 0;
    /// Lower-left corner of the area drawn in that framebuffer (0, 0 unless the context draws into a
    /// viewport of another program's window).
    virtual int originX() const { return 0; }
    /// See originX().
    virtual int originY() const { return 0; }
    /// Where a frame's passes draw: a framebuffer and the area drawn in it (lower-left corner, size).
    struct DrawTarget {
        unsigned framebuffer = 0;  ///< framebuffer object name (0: the window's default framebuffer)
        int x = 0;                 ///< lower-left corner of the area drawn
        int y = 0;                 ///< see x
        int width = 0;             ///< size of the area drawn
        int height = 0;            ///< see width
    };
    /// Where passes draw now: this context's framebuffer and area, unless redirectDrawing() sent
    /// them to another target (a reduced-resolution frame, see ScaledFrame).
    DrawTarget drawTarget() const;
    /// Sends every pass to `target` until called with std::nullopt. Passes bind drawTarget() rather
    /// than framebuffer(), so a renderer can draw a frame off screen without each pass knowing.
    void redirectDrawing(std::optional<DrawTarget> target) { redirect_ = target; }
    /// Resizes the framebuffer (headless) or the window. Throws std::invalid_argument unless both
    /// sizes are positive and within the implementation's limits.
    virtual void resize(int width, int height) = 0;
    /// Ends a frame: swaps buffers (window) or waits until the frame is complete (headless).
    virtual void present() = 0;
    /// Whether the frame is drawn off screen.
    virtual bool headless() const = 0;
    /// Processes window events (no-op headless).
    virtual void pollEvents() {}
    /// Whether the user asked to close the window (always false headless).
    virtual bool shouldClose() const { return false; }

    /// The GL function table, loaded for this context. Make the context current before calling.
    const GladGLContext& gl() const { return *gl_; }
    /// "<kind>: <GL_VERSION>, <GL_RENDERER>", for logs and reports.
    const std::string& description() const { return description_; }
    /// What made it: "OSMesa (headless)", "EGL device (headless)", "EGL surfaceless (headless)", "GLFW window".
    const std::string& kind() const { return kind_; }
    /// GL_VENDOR, GL_RENDERER and GL_VERSION as the driver gives them.
    const std::string& vendor() const { return vendor_; }
    /// See vendor().
    const std::string& renderer() const { return renderer_; }
    /// See vendor().
    const std::string& version() const { return version_; }

protected:
    GlContext();
    /// Loads the function table with `loader` (context current), checks that the version is at
    /// least 3.3 and records the description; throws std::runtime_error naming `kind` otherwise.
    void loadFunctions(ProcLoader loader, const std::string& kind);

private:
    std::unique_ptr<GladGLContext> gl_;
    std::string description_, kind_, vendor_, renderer_, version_;
    std::optional<DrawTarget> redirect_;
};

}  // namespace throng
