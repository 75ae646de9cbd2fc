#pragma once
// A GL context in a window (GLFW, core profile 3.3). Needs a display; see createContext() for the
// choice between a window and headless rendering.

#include <string>

#include "throng/render/GlContext.h"

struct GLFWwindow;

namespace throng {

/// A window with an OpenGL 3.3 core context, drawing into its default framebuffer.
class GlfwWindowContext final : public GlContext {
public:
    /// Opens a `width` x `height` window titled `title` (hidden when `visible` is false) and makes
    /// its context current; `vsync` ties present() to the display refresh. Throws
    /// std::invalid_argument for a bad size and std::runtime_error with GLFW's own message when
    /// GLFW cannot start (no display) or the window or context cannot be created.
    GlfwWindowContext(int width, int height, const std::string& title, bool visible = true, bool vsync = false);
    ~GlfwWindowContext() override;

    void makeCurrent() override;
    unsigned framebuffer() const override { return 0; }
    int width() const override;
    int height() const override;
    void resize(int width, int height) override;
    void present() override;
    bool headless() const override { return false; }
    void pollEvents() override;
    bool shouldClose() const override;

    /// The GLFW window, for input handling by applications.
    GLFWwindow* window() const { return window_; }

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace throng
