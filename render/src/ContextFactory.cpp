#include "throng/render/ContextFactory.h"

#include <cstdlib>
#include <stdexcept>

#include "throng/render/EglContext.h"
#include "throng/render/GlfwWindowContext.h"
#ifdef THRONG_HAVE_OSMESA
#include "throng/render/OsMesaContext.h"
#endif

namespace throng {

bool displayAvailable() {
    const auto set = [](const char* name) {
        const char* v = std::getenv(name);
        return v && *v;
    };
    return set("DISPLAY") || set("WAYLAND_DISPLAY");
}

GlApi glApiFromName(const std::string& text) {
    if (text == "auto") return GlApi::Auto;
    if (text == "window") return GlApi::Window;
    if (text == "egl") return GlApi::Egl;
    if (text == "osmesa") return GlApi::OsMesa;
    throw std::invalid_argument("'" + text + "' is not a GL context (auto, window, egl, osmesa)");
}

const char* glApiName(GlApi api) {
    switch (api) {
        case GlApi::Window: return "window";
        case GlApi::Egl: return "egl";
        case GlApi::OsMesa: return "osmesa";
        case GlApi::Auto: break;
    }
    return "auto";
}

namespace {

// EGL headless: a hardware device when one is present, else surfaceless. Throws ContextUnavailable naming both failures.
std::shared_ptr<GlContext> eglContext(const ContextOptions& o, bool surfacelessToo) {
    std::string device = "no hardware EGL device is listed";
    if (EglContext::hardwareDevicePresent()) try {
        return std::make_shared<EglContext>(o.width, o.height, EglContext::Platform::Device);
    } catch (const std::runtime_error& e) {
        device = e.what();
    }
    if (!surfacelessToo) throw ContextUnavailable(device);
    try {
        return std::make_shared<EglContext>(o.width, o.height, EglContext::Platform::Surfaceless);
    } catch (const std::runtime_error& e) {
        throw ContextUnavailable("no EGL context with OpenGL 3.3 core (device: " + device + "; surfaceless: " + e.what() +
                                 "): try --gl osmesa");
    }
}

// OSMesa's software context; throws std::runtime_error when it cannot be made or this build has none.
std::shared_ptr<GlContext> osMesaContext(const ContextOptions& o) {
#ifdef THRONG_HAVE_OSMESA
    return std::make_shared<OsMesaContext>(o.width, o.height);
#else
    (void)o;
    throw std::runtime_error("this build has no OSMesa (configured with THRONG_WITH_OSMESA=OFF)");
#endif
}

}  // namespace

std::shared_ptr<GlContext> createContext(const ContextOptions& options, std::string* fallbackReason) {
    if (options.width <= 0 || options.height <= 0)
        throw std::invalid_argument("createContext: size " + std::to_string(options.width) + " x " +
                                    std::to_string(options.height) + " must be positive");
    switch (options.api) {
        case GlApi::Window:
            if (!displayAvailable()) throw ContextUnavailable("no window: no display (neither DISPLAY nor WAYLAND_DISPLAY is set): try --gl egl");
            try {
                return std::make_shared<GlfwWindowContext>(options.width, options.height, options.title, true, options.vsync);
            } catch (const std::runtime_error& e) {
                throw ContextUnavailable(std::string("no window: ") + e.what() + ": try --gl egl");
            }
        case GlApi::Egl: return eglContext(options, true);
        case GlApi::OsMesa:
            try {
                return osMesaContext(options);
            } catch (const std::runtime_error& e) {
                throw ContextUnavailable(std::string(e.what()) + ": try --gl egl");
            }
        case GlApi::Auto: break;
    }
    std::string windowFailure;
    if (options.window) {
        if (!displayAvailable()) {
            windowFailure = "no display (neither DISPLAY nor WAYLAND_DISPLAY is set)";
        } else {
            try {
                return std::make_shared<GlfwWindowContext>(options.width, options.height, options.title, true,
                                                           options.vsync);
            } catch (const std::runtime_error& e) {
                windowFailure = e.what();
            }
        }
    }
    if (fallbackReason) *fallbackReason = windowFailure;
    // A GPU first, then the software rasterisers: OSMesa (what the goldens were made with), then
    // Mesa's surfaceless EGL (the same rasteriser where OSMesa is not installed).
    std::string failures;
    if (EglContext::hardwareDevicePresent()) try {
        return eglContext(options, false);
    } catch (const std::runtime_error& e) {
        failures += std::string("EGL device: ") + e.what() + ". ";
    }
    try {
        return osMesaContext(options);
    } catch (const std::runtime_error& e) {
        failures += std::string("OSMesa: ") + e.what() + ". ";
    }
    try {
        return std::make_shared<EglContext>(options.width, options.height, EglContext::Platform::Surfaceless);
    } catch (const std::runtime_error& e) {
        failures += std::string("EGL surfaceless: ") + e.what() + ".";
    }
    throw std::runtime_error("createContext: no OpenGL context could be created. " +
                             (windowFailure.empty() ? std::string() : "Window: " + windowFailure + ". ") + failures);
}

}  // namespace throng
