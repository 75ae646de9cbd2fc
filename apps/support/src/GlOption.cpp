#include "throng/support/GlOption.h"

#include "throng/support/Validators.h"

namespace throng::support {

void declareGlOption(CLI::App& app, std::string& value) {
    app.add_option("--gl", value,
                   "GL context: auto (a window when there is a display and --headless is not given, else EGL on a GPU, "
                   "else OSMesa, else EGL surfaceless), window, egl (a GPU, else Mesa's surfaceless platform) or osmesa")
        ->type_name("KIND")
        ->check(oneOf({"auto", "window", "egl", "osmesa"}));
}

}  // namespace throng::support
