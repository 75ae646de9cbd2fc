// throng-vtk: a Throng crowd inside an ordinary VTK application. Builds the world a scene file
// declares (as throng-town does), then shows it with VTK: the town's tiles as VTK polydata in a
// vtkActor, the crowd as a throng::vtk::CrowdProp (each render runs the actor cascade for VTK's
// camera and draws the visible actors, sharing the depth buffer with the tiles), VTK's trackball
// camera, and a vtkTextActor with the cascade's statistics. --draw vtk (the default) draws the
// actors' meshes through a VTK mapper; --draw throng draws them with Throng's renderer in VTK's
// context, with the key-pose caches and impostors the scene declares (baked at start in an
// offscreen OSMesa context: the atlases are CPU images the renderer uploads into VTK's).
//
// In a window the simulation steps on a repeating timer of the interactor. With --screenshot FILE
// nothing is shown: the world steps --frames times, the view of the scene's camera path at that
// time is rendered offscreen and written as a PNG (Debian's VTK renders through X: run it under
// xvfb-run on a machine without a display).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkLightKit.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include "VtkOptions.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/render/ImpostorSet.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneError.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/support/ProgressBar.h"
#include "throng/support/SceneImpostors.h"
#include "throng/vtk/CrowdProp.h"
#include "throng/vtk/ScenePolyData.h"
#include "throng/vtk/WindowPng.h"

using namespace throng;

namespace {

// Exit codes: a bad command line or a scene that does not build; a failure while running.
constexpr int kBadInput = 2, kRunFailed = 3;

// The scene file the options name, with --actors and --seed applied. Throws sim::SceneError (a
// bad scene file) or std::invalid_argument (more actors than the town can hold).
sim::SceneDescription loadScene(const vtkapp::VtkOptions& o) {
    sim::SceneDescription scene = sim::parseSceneFile(o.scene);
    if (o.actors) sim::scaleActors(scene, *o.actors);
    if (o.seed) scene.seed = *o.seed;
    return scene;
}

// The world of `scene`, built with a progress bar. Throws sim::SceneError (with the JSON path) or
// std::runtime_error (a navigation mesh that cannot be built).
std::unique_ptr<sim::Simulation> buildWorld(const sim::SceneDescription& scene) {
    support::ProgressBar bar("building", 100);
    auto world = sim::Simulation::build(scene, [&](const std::string& stage, double f) { bar.update(std::size_t(f * 100), stage); });
    bar.finish(std::to_string(world->crowd().size()) + " actors");
    return world;
}

// Actors drawn in the last render, by how (distinct actors of the draw list's items; the list also
// holds the scene's own items, and an actor may have several).
struct DrawnActors {
    std::uint64_t meshes = 0, keyPoses = 0, impostors = 0;
    std::uint64_t total() const { return meshes + keyPoses + impostors; }
};

// The cascade's statistics of the last render, as the overlay shows them: where actors left it
// (seed 002 Table 2; occluded when the scene declares occlusion), the actors drawn, and the
// cascade's time (APP and CULL; building the meshes and drawing them are not in it).
std::string statisticsText(throng::vtk::CrowdProp& crowd, const DrawnActors& drawn) {
    const ActorFrameStatistics& s = crowd.GetLastStatistics();
    char how[160] = "";
    if (drawn.keyPoses + drawn.impostors > 0)
        std::snprintf(how, sizeof how, ": %llu meshes, %llu key-poses, %llu impostors", (unsigned long long)drawn.meshes,
                      (unsigned long long)drawn.keyPoses, (unsigned long long)drawn.impostors);
    char text[640];
    std::snprintf(text, sizeof text,
                  "actors %llu   culled with group %llu   occluded %llu\n"
                  "A %llu   B %llu   C1 %llu   C2 %llu   C3 %llu (C3.1 %llu, C3.2 %llu)\n"
                  "drawn %llu actors%s (%llu triangles)   APP+CULL %.2f ms",
                  (unsigned long long)s.actorsInScene, (unsigned long long)s.culledWithGroup,
                  (unsigned long long)(s.occludedWithGroup + s.occludedRefpoint + s.occludedSklsroot), (unsigned long long)s.a,
                  (unsigned long long)s.b, (unsigned long long)s.c1, (unsigned long long)s.c2,
                  (unsigned long long)(s.c3_1 + s.c3_2), (unsigned long long)s.c3_1, (unsigned long long)s.c3_2,
                  (unsigned long long)drawn.total(), how, (unsigned long long)crowd.GetLastTriangles(), s.appCullMs());
    return text;
}

// Puts a Throng camera (a point on the scene's camera path) into VTK's camera: the same eye, view
// direction, up, vertical field of view and clipping range.
void placeCamera(vtkCamera& to, const Camera& from) {
    const Mat4& view = from.view();  // rows of its rotation: the eye's right, up and backward axes
    const Vec3 up(view[0][1], view[1][1], view[2][1]);
    const Vec3 forward(-view[0][2], -view[1][2], -view[2][2]);
    const Vec3 eye = from.eye();
    to.SetPosition(eye.x, eye.y, eye.z);
    to.SetFocalPoint(eye.x + 10.0 * forward.x, eye.y + 10.0 * forward.y, eye.z + 10.0 * forward.z);
    to.SetViewUp(up.x, up.y, up.z);
    to.SetViewAngle(from.fovY() * 180.0 / std::numbers::pi);
    to.SetClippingRange(from.nearDistance(), from.farDistance());
}

// The VTK side of the program: one renderer holding the town's tiles, the crowd prop and the
// statistics overlay, in a render window of the asked size.
class TownView {
public:
    // `throngDrawing`: Throng's renderer draws the crowd (with the scene's key-pose caches and
    // impostors), else a VTK mapper (meshes only). Throws std::runtime_error if impostors cannot be
    // baked.
    TownView(sim::Simulation& world, int width, int height, bool offscreen, bool throngDrawing) : world_(world) {
        crowd_->SetScene(&world.crowd(), &world.root());
        crowd_->SetThrongDrawing(throngDrawing);
        configureCascade(*crowd_->GetProcessor(), throngDrawing);

        throng::vtk::ScenePolyDataStatistics tileStats;
        tilesMapper_->SetInputData(throng::vtk::scenePolyData(world.root(), &tileStats));
        tilesMapper_->ScalarVisibilityOff();  // cell data "mesh" numbers the tiles: not a colour
        tiles_->SetMapper(tilesMapper_);
        tiles_->GetProperty()->SetColor(0.45, 0.46, 0.50);  // darker than most actors, which stand out
        std::fprintf(stderr, "throng-vtk: town of %llu meshes, %llu triangles\n", (unsigned long long)tileStats.meshes,
                     (unsigned long long)tileStats.triangles);

        overlay_->GetTextProperty()->SetFontSize(std::max(10, height / 45));
        overlay_->GetTextProperty()->SetColor(1.0, 1.0, 1.0);
        overlay_->GetTextProperty()->SetBackgroundColor(0.0, 0.0, 0.0);
        overlay_->GetTextProperty()->SetBackgroundOpacity(0.55);
        overlay_->SetDisplayPosition(8, 8);

        renderer_->AddActor(tiles_);
        renderer_->AddViewProp(crowd_);
        renderer_->AddActor2D(overlay_);
        renderer_->SetBackground(0.53, 0.68, 0.86);
        // Lights placed relative to the camera (key from above, fill, back): VTK's default headlight
        // alone leaves roofs and streets dark whenever the camera looks across the town.
        vtkNew<vtkLightKit> lights;
        lights->AddLightsToRenderer(renderer_);
        placeCamera(*renderer_->GetActiveCamera(), world.camera().at(world.now().time, double(width) / double(height)));

        window_->SetOffScreenRendering(offscreen ? 1 : 0);
        window_->SetSize(width, height);
        window_->SetWindowName(("Throng in VTK: " + world.description().name).c_str());
        window_->AddRenderer(renderer_);
    }

    vtkRenderWindow& window() { return *window_; }
    vtkRenderer& renderer() { return *renderer_; }

    // Renders the view, then puts this render's cascade statistics in the overlay (shown by the
    // next render: the prop learns them while the renderer draws).
    void render() {
        window_->Render();
        overlay_->SetInput(statisticsText(*crowd_, actorsDrawn()).c_str());
    }

    // The view of the scene's camera path at the world's current time, rendered twice so that the
    // overlay shows that very render's statistics, written to `path` as a PNG. Throws
    // std::runtime_error if it cannot be written.
    void screenshot(const std::string& path) {
        const int* size = window_->GetSize();
        placeCamera(*renderer_->GetActiveCamera(), world_.camera().at(world_.now().time, double(size[0]) / double(size[1])));
        render();
        Stopwatch watch;  // the second render: the crowd's GL objects exist by then
        render();
        const double renderMs = watch.elapsedMs();
        throng::vtk::writeWindowPng(*window_, path);
        const DrawnActors drawn = actorsDrawn();
        std::fprintf(stderr, "throng-vtk: drew %llu actors: %llu meshes, %llu key-poses, %llu impostors (%llu triangles) in a %.1f ms render\n",
                     (unsigned long long)drawn.total(), (unsigned long long)drawn.meshes, (unsigned long long)drawn.keyPoses,
                     (unsigned long long)drawn.impostors, (unsigned long long)crowd_->GetLastTriangles(), renderMs);
        if (const CrowdRenderStatistics* r = crowd_->GetLastRenderStatistics())  // what Throng's renderer drew of them
            std::fprintf(stderr, "throng-vtk: Throng's renderer: %llu key-pose items, %llu impostor quads\n",
                         (unsigned long long)r->keyPoseItems, (unsigned long long)r->quads.instances);
    }

private:
    // Actors the last render drew, by representation.
    DrawnActors actorsDrawn() {
        drawnStamp_.resize(world_.crowd().size(), 0);
        ++stamp_;
        DrawnActors drawn;
        for (const DrawItem& item : crowd_->GetProcessor()->drawList().items()) {
            if (item.actor == kNoActor || item.actor >= drawnStamp_.size() || drawnStamp_[item.actor] == stamp_) continue;
            if (item.representation != Representation::Mesh && !crowd_->GetThrongDrawing()) continue;  // the mapper skips them
            drawnStamp_[item.actor] = stamp_;
            switch (item.representation) {
                case Representation::Mesh: ++drawn.meshes; break;
                case Representation::KeyPose: ++drawn.keyPoses; break;
                case Representation::Impostor: ++drawn.impostors; break;
            }
        }
        return drawn;
    }

    // The cascade as throng-town runs it for this scene (LOD scale, occlusion when declared) and,
    // when Throng's renderer draws, the key-pose caches and impostors the scene declares; the VTK
    // mapper draws meshes only, so then every actor stays a mesh.
    void configureCascade(ActorProcessor& processor, bool throngDrawing) {
        const sim::RepresentationDescription& r = world_.description().representation;
        processor.setLodScale(r.lodScale);
        if (r.occlusion) processor.setOcclusion(r.occlusion);
        if (!throngDrawing) return;
        world_.attachKeyPoseCaches(processor);
        if (r.impostorDistance > 0.0) {
            // Baked offscreen: the atlases are CPU images, uploaded by the renderer into VTK's context.
            impostors_ = support::bakeSceneImpostors(createContext({.width = 64, .height = 64}), world_, true);
            impostors_->attach(processor, r.impostorDistance, r.hysteresis * r.impostorDistance);
        }
    }

    sim::Simulation& world_;
    vtkNew<vtkRenderWindow> window_;
    vtkNew<vtkRenderer> renderer_;
    vtkNew<vtkPolyDataMapper> tilesMapper_;
    vtkNew<vtkActor> tiles_;
    vtkNew<throng::vtk::CrowdProp> crowd_;
    std::unique_ptr<ImpostorSet> impostors_;  // the atlases the processor's impostor items show
    vtkNew<vtkTextActor> overlay_;
    std::vector<std::uint64_t> drawnStamp_;  // per actor: the last count that saw it drawn
    std::uint64_t stamp_ = 0;
};

// The window: VTK's trackball camera, and a repeating timer that steps the world and renders.
class Viewer {
public:
    // `steps`: the window closes after that many timer steps (none: when the user closes it).
    Viewer(sim::Simulation& world, TownView& view, std::optional<std::int64_t> steps) : world_(world), view_(view), steps_(steps) {}

    // Runs until the window closes (or Q/E, or the steps are done). Throws what a step throws.
    void run() {
        vtkNew<vtkRenderWindowInteractor> interactor;
        vtkNew<vtkInteractorStyleTrackballCamera> style;
        interactor->SetInteractorStyle(style);
        interactor->SetRenderWindow(&view_.window());
        interactor->Initialize();
        vtkNew<vtkCallbackCommand> onTimer;
        onTimer->SetClientData(this);
        onTimer->SetCallback([](vtkObject*, unsigned long, void* self, void*) { static_cast<Viewer*>(self)->tick(); });
        interactor->AddObserver(vtkCommand::TimerEvent, onTimer);
        const int ms = std::max(1, int(std::lround(1000.0 * world_.description().step)));
        interactor->CreateRepeatingTimer(unsigned(ms));
        view_.render();
        interactor->Start();
        if (failure_) std::rethrow_exception(failure_);
    }

private:
    // One timer tick: a simulation step, then a render. An exception must not cross VTK's event
    // loop: it is kept, the loop ends, and run() throws it.
    void tick() {
        if (failure_ || done_) return;
        try {
            world_.step();
            view_.render();
            if (steps_ && ++stepped_ >= *steps_) {
                done_ = true;
                view_.window().GetInteractor()->TerminateApp();
            }
        } catch (...) {
            failure_ = std::current_exception();
            view_.window().GetInteractor()->TerminateApp();
        }
    }

    sim::Simulation& world_;
    TownView& view_;
    std::optional<std::int64_t> steps_;
    std::int64_t stepped_ = 0;
    bool done_ = false;
    std::exception_ptr failure_;
};

// Steps the world `frames` times with a progress bar.
void stepWorld(sim::Simulation& world, std::int64_t frames) {
    support::ProgressBar bar("stepping", std::size_t(std::max<std::int64_t>(frames, 1)));
    for (std::int64_t f = 0; f < frames; ++f) {
        world.step();
        bar.update(std::size_t(f + 1));
    }
    bar.finish();
}

}  // namespace

int main(int argc, char** argv) {
    vtkapp::VtkOptions o;
    sim::SceneDescription scene;
    try {
        o = vtkapp::parseVtkOptions(argc, argv, THRONG_TOWN_DEFAULT_SCENE);
        scene = loadScene(o);
    } catch (const sim::SceneError& e) {
        std::fprintf(stderr, "throng-vtk: %s\n", e.what());
        return kBadInput;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "throng-vtk: %s\n%s", e.what(), vtkapp::vtkUsage().c_str());
        return kBadInput;
    }
    // Debian's VTK opens X even offscreen: without a display it would abort inside VTK.
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        std::fprintf(stderr, "throng-vtk: no X display (DISPLAY is not set): run it under xvfb-run -a%s\n",
                     o.screenshot.empty() ? ", with --screenshot FILE" : "");
        return kBadInput;
    }
    std::unique_ptr<sim::Simulation> world;
    try {
        world = buildWorld(scene);
    } catch (const std::exception& e) {  // SceneError while building, a navigation mesh
        std::fprintf(stderr, "\nthrong-vtk: %s\n", e.what());
        return kBadInput;
    }
    try {
        TownView view(*world, o.width, o.height, !o.screenshot.empty(), o.draw == "throng");
        if (!o.screenshot.empty()) {
            stepWorld(*world, o.frames);
            view.screenshot(o.screenshot);
            std::fprintf(stderr, "throng-vtk: %s after %lld steps (time %.2f s)\n", o.screenshot.c_str(), (long long)o.frames,
                         world->now().time);
        } else {
            Viewer(*world, view, o.framesGiven ? std::optional<std::int64_t>(o.frames) : std::nullopt).run();
            std::fprintf(stderr, "throng-vtk: window closed at time %.2f s\n", world->now().time);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-vtk: %s\n", e.what());
        return kRunFailed;
    }
    return 0;
}
