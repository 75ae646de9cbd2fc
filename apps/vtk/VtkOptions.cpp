#include "VtkOptions.h"

#include "throng/support/CommandLine.h"
#include "throng/support/SceneOptions.h"
#include "throng/support/Validators.h"

namespace throng::vtkapp {
namespace {

constexpr const char* kName = "throng-vtk";

// Declares every option of throng-vtk on `cl`, bound to `o` (the scene options as throng-town's).
void declare(support::CommandLine& cl, VtkOptions& o) {
    using namespace support;
    CLI::App& app = cl.app();
    declareSceneOptions(app, o.scene, o.actors, o.seed);
    app.add_option("--screenshot", o.screenshot,
                   "no window: step --frames times, write a PNG of the scene camera's view at that time, exit")
        ->type_name("FILE")
        ->check(fileToWrite());
    app.add_option("--frames", o.frames, "steps before the --screenshot picture (in a window: quit after N steps when given)")
        ->type_name("N")
        ->check(wholeNumber(0, 100'000'000))
        ->capture_default_str();
    app.add_option("--width", o.width, "window or picture width in pixels")->type_name("W")->check(wholeNumber(16, 8192))->capture_default_str();
    app.add_option("--height", o.height, "window or picture height in pixels")->type_name("H")->check(wholeNumber(16, 8192))->capture_default_str();
    app.add_option("--draw", o.draw,
                   "who draws the crowd: vtk (a VTK mapper, meshes skinned on the CPU; no impostors or key-pose caches) "
                   "or throng (Throng's renderer in VTK's context: GPU skinning, textures, the scene's key-pose caches and impostors)")
        ->type_name("vtk|throng")
        ->check(oneOf({"vtk", "throng"}))
        ->capture_default_str();
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
    support::CommandLine::parseOrExitOnHelp(
        kName,
        "A Throng crowd in a VTK scene: the town a scene file declares, its tiles as VTK polydata\n"
        "and its crowd drawn by throng::vtk::CrowdProp (the actor cascade run for VTK's camera),\n"
        "with VTK's trackball interactor and the cascade's statistics as a text overlay.",
        argc, argv, [&](support::CommandLine& cl) { declare(cl, o); },
        [&](support::CommandLine& cl) { o.framesGiven = cl.app().count("--frames") > 0; });
    return o;
}

}  // namespace throng::vtkapp
