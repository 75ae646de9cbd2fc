// bench_vtk_crowd_prop: a crowd drawn inside VTK by throng::vtk::CrowdProp, both ways (the cascade
// for VTK's camera, then CPU skinning into one poly data and a VTK mapper, or Throng's renderer in
// VTK's context), beside the same crowd drawn by Throng's renderer in its own window (ActorProcessor +
// CrowdRenderer: GPU skinning, instancing), on the same state and the same camera, each frame back to
// back, the paths taking turns going first. All draw through Mesa's llvmpipe (VTK in offscreen
// windows of the X display, Throng alone in a GLFW window on the same display), at the same size, the
// actors only (no town).
//
// Reported per path and crowd size: APP+CULL (the cascade, the same in both), what the path adds
// before GL (CrowdProp: skinning and filling the poly data), the render including the GL finishing
// (vtkRenderWindow::Render with a glFinish; CrowdRenderer::drawFrame with its passes finished), the
// whole frame, and the actors and triangles drawn (equal when both draw the same draw list).
//
// usage: bench_vtk_crowd_prop [--actors 1000,4000] [--frames 20] [--width 1280] [--height 720]
// (needs an X display: run under xvfb-run -a)

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include "throng/actors/ActorProcessor.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/render/GlContext.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/testkit/TownSpread.h"
#include "throng/bench/Experiment.h"
#include "throng/vtk/CameraFromVtk.h"
#include "throng/vtk/Chart.h"
#include "throng/vtk/CrowdProp.h"

using namespace throng;

namespace {

struct Options {
    std::vector<std::int64_t> actors{1000, 4000};
    int frames = 20;
    int width = 1280, height = 720;
};

struct Totals {
    double appCull = 0, build = 0, render = 0, frame = 0, drawn = 0, triangles = 0;
};

// One VTK window holding a CrowdProp, drawing through the mapper or with Throng's renderer.
struct VtkPath {
    vtkNew<vtkRenderWindow> window;
    vtkNew<vtkRenderer> renderer;
    vtkSmartPointer<throng::vtk::CrowdProp> prop = vtkSmartPointer<throng::vtk::CrowdProp>::New();
    Totals totals;
    VtkPath(Crowd& crowd, Node& root, bool throngDrawing, const Options& o) {
        window->SetOffScreenRendering(1);
        window->SetSize(o.width, o.height);
        renderer->SetBackground(0.55, 0.66, 0.80);
        window->AddRenderer(renderer);
        vtkCamera* camera = renderer->GetActiveCamera();  // a pedestrian in the spread, as bench_vtk_culler
        camera->SetPosition(0, 1.7, 0);
        camera->SetFocalPoint(100, 1.7, 20);
        camera->SetViewUp(0, 1, 0);
        camera->SetViewAngle(1.0 * 180.0 / 3.14159265358979323846);
        camera->SetClippingRange(0.1, 1500.0);
        prop->SetScene(&crowd, &root);
        prop->SetThrongDrawing(throngDrawing);
        renderer->AddViewProp(prop);
    }
    void frame(bool measured) {
        window->MakeCurrent();  // another path's context may be current
        Stopwatch watch;
        window->Render();
        window->WaitForCompletion();
        const double ms = watch.elapsedMs();
        if (!measured) return;
        const ActorFrameStatistics& s = prop->GetLastStatistics();
        const bool throngDrawing = prop->GetThrongDrawing();
        totals.appCull += s.appCullMs();
        totals.build += throngDrawing ? 0.0 : prop->GetLastBuildMs();
        totals.render += ms - s.appCullMs() - (throngDrawing ? 0.0 : prop->GetLastBuildMs());
        totals.frame += ms;
        totals.drawn += double(s.drawItems);
        totals.triangles += double(prop->GetLastTriangles());
    }
};

// Throng's own window: GLX on the same display as VTK (OSMesa and GLX in one process crash Mesa),
// made once for every crowd size: the display then always has a client, so a virtual X server
// (xvfb-run) never resets between sizes, which made the next window's connection fail at random.
std::shared_ptr<GlContext> throngWindow(const Options& o) {
    ContextOptions contextOptions;
    contextOptions.width = o.width;
    contextOptions.height = o.height;
    contextOptions.window = true;
    std::string fallback;
    auto context = createContext(contextOptions, &fallback);
    if (!fallback.empty()) throw std::runtime_error("no GLFW window on the X display: " + fallback);
    return context;
}

void run(std::int64_t count, const Options& o, const std::shared_ptr<GlContext>& context) {
    Crowd crowd;
    const auto actors = std::size_t(count);
    const testkit::TownSpread town = testkit::buildTownSpread(crowd, actors, 40.0 * std::sqrt(double(actors)));
    VtkPath mapper(crowd, *town.root, false, o), inVtk(crowd, *town.root, true, o);

    context->makeCurrent();  // VTK's windows made theirs current since the last size
    CrowdRendererOptions drawOptions;
    drawOptions.finishPasses = true;
    CrowdRenderer throngDraw(context, drawOptions);
    ActorProcessor processor(crowd);
    Totals alone;
    const auto throngFrame = [&](bool measured) {
        const Camera view = throng::vtk::cameraFromVtk(*mapper.renderer->GetActiveCamera(), double(o.width) / double(o.height));
        context->makeCurrent();
        Stopwatch watch;
        const ActorFrameStatistics s = processor.processFrame(*town.root, view, crowd.time());
        const double appCull = watch.elapsedMs();
        throngDraw.drawFrame(view, processor.drawList());
        const double ms = watch.elapsedMs();
        if (!measured) return;
        alone.appCull += appCull;
        alone.render += ms - appCull;
        alone.frame += ms;
        alone.drawn += double(s.drawItems);
        alone.triangles += double(throngDraw.statistics().meshes.triangles);
    };

    FrameContext now;
    for (int f = -2; f < o.frames; ++f) {  // two unmeasured frames warm the GLs
        now.time = double(now.frame) / 30.0;
        crowd.step(now);
        ++now.frame;
        for (int turn = 0; turn < 3; ++turn) {  // the paths take turns going first
            const int path = (turn + f + 2) % 3;
            if (path == 0) mapper.frame(f >= 0);
            else if (path == 1) inVtk.frame(f >= 0);
            else throngFrame(f >= 0);
        }
        if (f >= 0) std::fprintf(stderr, "\rbench_vtk_crowd_prop: %zu actors, frame %d of %d", actors, f + 1, o.frames);
    }
    std::fprintf(stderr, "\n");
    const double n = double(o.frames);
    const auto row = [&](const char* path, const Totals& t) {
        std::printf("| %zu | %s | %.2f | %.2f | %.2f | %.2f | %.2fx | %.0f | %.0f |\n", actors, path, t.appCull / n, t.build / n, t.render / n,
                    t.frame / n, t.frame / std::max(alone.frame, 1e-9), t.drawn / n, t.triangles / n);
    };
    row("CrowdProp, VTK mapper (CPU skinning)", mapper.totals);
    row("CrowdProp, Throng's renderer in VTK's context", inVtk.totals);
    row("Throng's renderer in its own window", alone);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    bench::Experiment experiment("bench_vtk_crowd_prop", "A crowd drawn inside VTK (CrowdProp) beside Throng's own renderer, same state and camera",
                                 0, {});
    CLI::App& app = experiment.app();
    app.add_option("--actors", o.actors, "crowd sizes")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(CLI::Range(1, 1000000));
    app.add_option("--frames", o.frames, "measured frames per size")->check(CLI::Range(1, 100000));
    app.add_option("--width", o.width, "image width")->check(CLI::Range(16, 8192));
    app.add_option("--height", o.height, "image height")->check(CLI::Range(16, 8192));
    if (const auto code = experiment.parse(argc, argv)) return *code;
    if (!throng::vtk::displayAvailable()) {
        std::fprintf(stderr, "bench_vtk_crowd_prop: no X display (Debian's VTK renders through X): run under xvfb-run -a\n");
        return 2;
    }
    try {
        std::printf("| actors | path | APP+CULL ms | skinning and poly data ms | render ms | frame ms | vs Throng alone | items drawn | triangles |\n"
                    "|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
        const std::shared_ptr<GlContext> window = throngWindow(o);
        for (std::int64_t a : o.actors) run(a, o, window);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_vtk_crowd_prop: %s\n", e.what());
        return 1;
    }
    return 0;
}
