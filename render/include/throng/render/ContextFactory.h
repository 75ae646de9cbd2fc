#pragma once
// Chooses and creates a GL context: a window when one is asked for and a display exists, else a
// headless OSMesa context, so that one binary serves both.

#include <memory>
#include <string>

#include "throng/render/GlContext.h"

namespace throng {

/// What kind of context to create and its framebuffer size.
struct ContextOptions {
    int width = 1280;              ///< pixels
    int height = 720;              ///< pixels
    bool window = false;           ///< prefer a window (used only when a display exists)
    std::string title = "Throng";  ///< window title
    bool vsync = false;            ///< window: wait for the display refresh in present()
};

/// Whether a window system is reachable (DISPLAY or WAYLAND_DISPLAY is set).
bool displayAvailable();

/// Creates a window context when `options.window` is set and a display exists, otherwise (or if
/// the window cannot be created) a headless OSMesa context. When a window was asked for but not
/// created, `fallbackReason` (if given) receives why. Throws std::runtime_error naming every
/// failure when no context can be created, std::invalid_argument for a bad size.
std::shared_ptr<GlContext> createContext(const ContextOptions& options, std::string* fallbackReason = nullptr);

}  // namespace throng
