#include "throng/support/GlOption.h"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "throng/render/ContextFactory.h"
#include "throng/render/EglContext.h"
#include "throng/support/Validators.h"

namespace throng::support {

void declareGlOption(CLI::App& app, std::string& value, bool window) {
    const std::string kinds = "egl (a GPU, else Mesa's surfaceless platform) or osmesa";
    app.add_option("--gl", value,
                   window ? "GL context: auto (a window when there is a display and --headless is not given, else EGL on a GPU, "
                            "else OSMesa, else EGL surfaceless), window, " + kinds
                          : "GL context, off-screen: auto (EGL on a GPU, else OSMesa, else EGL surfaceless), " + kinds)
        ->type_name("KIND")
        ->check(window ? oneOf({"auto", "window", "egl", "osmesa"}) : oneOf({"auto", "egl", "osmesa"}));
    app.add_flag_callback(
        "--gl-info",
        [] {
            std::fputs(headlessGlReport().c_str(), stdout);
            std::fflush(stdout);
            std::exit(0);
        },
        "print the EGL devices and the headless GL context each --gl gives on this machine, then exit");
}

std::optional<int> refuseUnavailableGl(const std::string& program, const std::string& gl) {
    if (gl != "egl" && gl != "osmesa") return std::nullopt;
    try {
        (void)createContext({.width = 16, .height = 16, .api = glApiFromName(gl)});
    } catch (const ContextUnavailable& e) {
        std::fprintf(stderr, "%s: --gl %s: %s\n", program.c_str(), gl.c_str(), e.what());
        return 2;
    }
    return std::nullopt;
}

std::string headlessGlReport() {
    std::string out;
    const auto devices = EglContext::devices();
    out += "EGL devices: " + std::to_string(devices.size()) +
           (devices.empty() ? " (no EGL library, driver or EGL_EXT_device_enumeration)\n" : "\n");
    for (const auto& d : devices) {
        out += "  " + std::to_string(d.index) + ": " + (d.software ? "software" : "hardware");
        if (!d.drmFile.empty()) out += ", " + d.drmFile;
        if (!d.vendor.empty() || !d.renderer.empty()) out += ", " + d.vendor + (d.vendor.empty() ? "" : " ") + d.renderer;
        out += "\n";
    }
    for (const GlApi api : {GlApi::Egl, GlApi::OsMesa, GlApi::Auto}) {
        out += api == GlApi::Auto ? std::string("auto (headless): ") : std::string("--gl ") + glApiName(api) + ": ";
        try {
            const auto context = createContext({.width = 16, .height = 16, .window = false, .api = api});
            out += context->kind() + "; " + context->vendor() + "; " + context->renderer() + "; " + context->version() + "\n";
        } catch (const std::runtime_error& e) {
            out += std::string("none: ") + e.what() + "\n";
        }
    }
    return out;
}

}  // namespace throng::support
