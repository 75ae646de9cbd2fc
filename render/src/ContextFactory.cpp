#include "throng/render/ContextFactory.h"

#include <cstdlib>
#include <stdexcept>

#include "throng/render/GlfwWindowContext.h"
#include "throng/render/OsMesaContext.h"

namespace throng {

bool displayAvailable() {
    const auto set = [](const char* name) {
        const char* v = std::getenv(name);
        return v && *v;
    };
    return set("DISPLAY") || set("WAYLAND_DISPLAY");
}

std::shared_ptr<GlContext> createContext(const ContextOptions& options, std::string* fallbackReason) {
    if (options.width <= 0 || options.height <= 0)
        throw std::invalid_argument("createContext: size " + std::to_string(options.width) + " x " +
                                    std::to_string(options.height) + " must be positive");
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
    try {
        auto context = std::make_shared<OsMesaContext>(options.width, options.height);
        if (fallbackReason) *fallbackReason = windowFailure;
        return context;
    } catch (const std::runtime_error& e) {
        throw std::runtime_error("createContext: no OpenGL context could be created. " +
                                 (windowFailure.empty() ? std::string() : "Window: " + windowFailure + ". ") +
                                 "Headless: " + e.what());
    }
}

}  // namespace throng
