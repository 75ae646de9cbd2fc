#include "VtkOptions.h"

#include <cstdio>
#include <cstdlib>

#include "throng/support/CommandLine.h"
#include "throng/support/Validators.h"

namespace throng::vtkapp {
namespace {

constexpr const char* kName = "throng-vtk";

// Declares every option of throng-vtk on `cl`, bound to `o` (the scene options as throng-town's).
void declare(support::CommandLine& cl, VtkOptions& o) {
    using namespace support;
    CLI::App& app = cl.app();
    app.add_option("--scene", o.scene, "scene file (JSON)")->type_name("FILE")->check(existingFile());
    app.add_option("--actors", o.actors, "total actors, the scene's groups scaled to it")
        ->type_name("N")
        ->check(wholeNumber(0, 2'000'000))
        ->default_str("the scene's");
    app.add_option("--seed", o.seed, "random seed")->type_name("N")->check(wholeNumberFrom(0))->default_str("the scene's");
    app.add_option("--screenshot", o.screenshot,
                   "no window: step --frames times, write a PNG of the scene camera's view at that time, exit")
        ->type_name("FILE")
        ->check(fileToWrite());
    app.add_option("--frames", o.frames, "--screenshot: simulation steps before the picture")
        ->type_name("N")
        ->check(wholeNumber(0, 100'000'000))
        ->capture_default_str();
    app.add_option("--width", o.width, "window or picture width in pixels")->type_name("W")->check(wholeNumber(16, 8192))->capture_default_str();
    app.add_option("--height", o.height, "window or picture height in pixels")->type_name("H")->check(wholeNumber(16, 8192))->capture_default_str();
    app.footer(
        "In the window: the simulation steps on a timer; VTK's trackball camera (left drag rotates, middle\n"
        "drag or Shift+left pans, wheel or right drag zooms, R frames the town), Q or E quits.\n"
        "Headless: xvfb-run -a throng-vtk --screenshot view.png (Debian's VTK renders through X).");
}

}  // namespace

std::string vtkUsage() { return support::CommandLine::hint(kName); }

VtkOptions parseVtkOptions(int argc, char** argv, const std::string& defaultScene) {
    VtkOptions o;
    o.scene = defaultScene;
    std::string help;
    {
        support::CommandLine cl(kName,
                                "A Throng crowd in a VTK scene: the town a scene file declares, its tiles as VTK polydata\n"
                                "and its crowd drawn by throng::vtk::CrowdProp (the actor cascade run for VTK's camera),\n"
                                "with VTK's trackball interactor and the cascade's statistics as a text overlay.");
        declare(cl, o);
        if (cl.parseOrThrow(argc, argv)) return o;
        help = cl.help();
    }
    std::fputs(help.c_str(), stdout);
    std::fflush(stdout);
    std::exit(0);
}

}  // namespace throng::vtkapp
