// CascadeCuller (the actor cascade as a vtkCuller) beside VTK's default vtkFrustumCoverageCuller on
// the same renderer, camera and props: 1,000 and 10,000 actor props (a town-like spread of walking
// humanoids, one actor group per 50 m block, a pedestrian's camera). Each iteration steps the crowd
// once and runs both ways on that state, back to back:
//   VTK:    every prop moved to its actor's Reference Point (VTK culls by the props' bounds, so they
//           must be current; the Reference Points, simulation state, are the cascade's phase 1,
//           whose time VTK's total includes), then vtkFrustumCoverageCuller::Cull (and once more on the unchanged
//           props, bounds cached: the frustum tests alone);
//   Throng: CascadeCuller::Cull (the cascade from the crowd's own state: Reference Points, CULL 1 on
//           the groups and Refpoint Bspheres, Skeleton Roots, CULL 2 on Sklsroot Bspheres, then the
//           poses of the survivors), then only the kept props moved (a scan of the actors' classes).
// No rendering: the cullers are called as vtkRenderer::AllocateTime calls them.

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCubeSource.h>
#include <vtkFrustumCoverageCuller.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include "throng/bench/MeanCounters.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/testkit/TownSpread.h"
#include "throng/vtk/CascadeCuller.h"

using namespace throng;

namespace {

void BM_CullActorProps(benchmark::State& state) {
    const auto actors = std::size_t(state.range(0));
    Crowd crowd;
    const testkit::TownSpread town = testkit::buildTownSpread(crowd, actors, 40.0 * std::sqrt(double(actors)));

    vtkNew<vtkRenderWindow> window;  // never rendered: it gives the renderer its aspect ratio
    window->SetSize(1600, 900);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    vtkCamera* camera = renderer->GetActiveCamera();  // the town's camera: 1 rad vertical, 16:9
    camera->SetPosition(0, 1.7, 0);
    camera->SetFocalPoint(100, 1.7, 20);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(1.0 * 180.0 / 3.14159265358979323846);
    camera->SetClippingRange(0.1, 1500.0);

    // One shared box (a standing person) for every prop.
    vtkNew<vtkCubeSource> box;
    box->SetBounds(-0.3, 0.3, 0.0, 1.8, -0.3, 0.3);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(box->GetOutputPort());
    mapper->Update();
    std::vector<vtkSmartPointer<vtkActor>> props(actors);
    auto cascade = vtkSmartPointer<throng::vtk::CascadeCuller>::New();
    cascade->SetScene(&crowd, town.root.get());
    for (ActorId id = 0; id < actors; ++id) {
        props[id] = vtkSmartPointer<vtkActor>::New();
        props[id]->SetMapper(mapper);
        cascade->SetActorProp(id, props[id]);
    }
    vtkNew<vtkFrustumCoverageCuller> frustum;
    std::vector<vtkProp*> list(actors);
    auto resetList = [&] {
        for (std::size_t i = 0; i < actors; ++i) list[i] = props[i];
    };
    auto move = [&](vtkProp* prop, ActorId id) {
        const Mat4& r = crowd.referencePoint(id);
        static_cast<vtkActor*>(prop)->SetPosition(r[3].x, r[3].y, r[3].z);
    };

    double refpointMs = 0, boundsMs = 0, cull1Ms = 0, rootsMs = 0, cull2Ms = 0;
    double vtkMoveMs = 0, vtkCullMs = 0, vtkCachedMs = 0, cascadeMs = 0, cascadePhasesMs = 0, keptMoveMs = 0, keptVtk = 0, keptCascade = 0;
    std::int64_t frames = 0;
    FrameContext context;
    auto step = [&] {
        context.time = double(context.frame) / 30.0;
        crowd.step(context);
        ++context.frame;
    };
    // Untimed warm-up of both (first-touch allocations, the mapper's bounds).
    step();
    resetList();
    int count = int(actors), initialized = 0;
    cascade->Cull(renderer, list.data(), count, initialized);
    for (ActorId id = 0; id < actors; ++id) move(props[id], id);
    resetList();
    count = int(actors), initialized = 0;
    frustum->Cull(renderer, list.data(), count, initialized);

    for (auto _ : state) {
        step();
        // VTK: move every prop, then cull by bounds.
        resetList();
        Stopwatch watch;
        for (ActorId id = 0; id < actors; ++id) move(props[id], id);
        vtkMoveMs += watch.elapsedMs();
        watch = Stopwatch();
        count = int(actors), initialized = 0;
        frustum->Cull(renderer, list.data(), count, initialized);
        vtkCullMs += watch.elapsedMs();
        keptVtk += count;
        // VTK again on the unchanged props: their bounds are cached, only the frustum tests remain.
        resetList();
        watch = Stopwatch();
        count = int(actors), initialized = 0;
        frustum->Cull(renderer, list.data(), count, initialized);
        vtkCachedMs += watch.elapsedMs();
        // Throng: the cascade from the crowd's state, then only the kept props move.
        resetList();
        watch = Stopwatch();
        count = int(actors), initialized = 0;
        cascade->Cull(renderer, list.data(), count, initialized);
        cascadeMs += watch.elapsedMs();
        const ActorFrameStatistics& s = cascade->GetLastStatistics();
        cascadePhasesMs += s.appMs + s.refpointMs + s.matricesBoundsMs + s.cullMs + s.skeletonRootMs + s.cull2Ms;
        refpointMs += s.refpointMs, boundsMs += s.matricesBoundsMs, cull1Ms += s.cullMs, rootsMs += s.skeletonRootMs, cull2Ms += s.cull2Ms;
        watch = Stopwatch();
        for (ActorId id = 0; id < actors; ++id) {  // the actors the cascade kept: B, C2, C3 after CULL 2
            const ActorClass c = crowd.actorClass(id);
            if (c == ActorClass::B || c == ActorClass::C2 || c == ActorClass::C3_1 || c == ActorClass::C3_2) move(props[id], id);
        }
        keptMoveMs += watch.elapsedMs();
        keptCascade += count;
        ++frames;
    }
    const double n = double(frames);
    state.counters["props"] = double(actors);
    // The Reference Points are simulation state both ways need: the cascade computes them (phase 1),
    // VTK's way reads them, so its total counts the cascade's phase-1 time too.
    bench::setMeanCounters(state, n, {{"vtk_kept", keptVtk}, {"cascade_kept", keptCascade}, {"vtk_move_ms", vtkMoveMs}, {"vtk_cull_ms", vtkCullMs},
                                      {"vtk_cull_cached_ms", vtkCachedMs}, {"vtk_total_ms", refpointMs + vtkMoveMs + vtkCullMs},
                                      {"cascade_cull_ms", cascadeMs}, {"cascade_cull12_ms", cascadePhasesMs}, {"refpoint_ms", refpointMs},
                                      {"bounds_ms", boundsMs}, {"cull1_ms", cull1Ms}, {"roots_ms", rootsMs}, {"cull2_ms", cull2Ms},
                                      {"cascade_move_kept_ms", keptMoveMs}, {"cascade_total_ms", cascadeMs + keptMoveMs}});
    state.counters["cull_ratio"] = vtkCullMs / cascadeMs;
    state.counters["total_ratio"] = (refpointMs + vtkMoveMs + vtkCullMs) / (cascadeMs + keptMoveMs);
}

BENCHMARK(BM_CullActorProps)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace
BENCHMARK_MAIN();
