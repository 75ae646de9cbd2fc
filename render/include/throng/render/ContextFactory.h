#pragma once
// Chooses and creates a GL context, so that one binary serves a desktop, a GPU server without a
// display and a CI machine without a GPU: a window when one is asked for and a display exists; else
// EGL on a hardware device (a GPU, no X server needed) when one is present; else OSMesa; else EGL
// on Mesa's surfaceless platform. Or exactly the kind asked for (--gl), and a clear error without it.

#include <memory>
#include <stdexcept>
#include <string>

#include "throng/render/GlContext.h"

namespace throng {

/// Which kind of GL context to create (the tools' --gl option).
enum class GlApi {
    Auto,    ///< the first that can be made: window (when asked for), EGL device, OSMesa, EGL surfaceless
    Window,  ///< a GLFW window on the display
    Egl,     ///< EGL headless: a hardware device when one is present, else Mesa's surfaceless platform
    OsMesa,  ///< Mesa's OSMesa (software, headless)
};

/// The kind named by `text` ("auto", "window", "egl", "osmesa"); throws std::invalid_argument otherwise.
GlApi glApiFromName(const std::string& text);
/// "auto", "window", "egl" or "osmesa".
const char* glApiName(GlApi api);

/// A context of the kind explicitly asked for cannot be made: the message says what is missing and
/// what to try instead (tools exit 2 with it, as for a bad option).
class ContextUnavailable : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// What kind of context to create and its framebuffer size.
struct ContextOptions {
    int width = 1280;              ///< pixels
    int height = 720;              ///< pixels
    bool window = false;           ///< prefer a window (used only when a display exists)
    std::string title = "Throng";  ///< window title
    bool vsync = false;            ///< window: wait for the display refresh in present()
    GlApi api = GlApi::Auto;       ///< the kind (Auto: `window` says whether a window is preferred)
};

/// Whether a window system is reachable (DISPLAY or WAYLAND_DISPLAY is set).
bool displayAvailable();

/// Creates the context `options.api` names. Auto: a window when `options.window` is set and a
/// display exists, else (or if the window cannot be created) a headless one: EGL on a hardware
/// device, OSMesa, or EGL surfaceless, the first that can be made. When a window was asked for but
/// not created, `fallbackReason` (if given) receives why. Throws ContextUnavailable when the kind
/// asked for explicitly cannot be made, std::runtime_error naming every failure when Auto finds
/// none, std::invalid_argument for a bad size.
std::shared_ptr<GlContext> createContext(const ContextOptions& options, std::string* fallbackReason = nullptr);

}  // namespace throng
