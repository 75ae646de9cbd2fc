// CascadeCuller inside a real render (under a virtual X display: xvfb-run): the renderer draws
// exactly the props the culler kept, plus the scenery that stands for no actor.

#include <gtest/gtest.h>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkConeSource.h>
#include <vtkCubeSource.h>
#include <vtkCullerCollection.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/vtk/CascadeCuller.h"
#include "throng/vtk/Chart.h"

using namespace throng;
using namespace throng::testkit;

TEST(CascadeCullerRender, TheRendererDrawsTheKeptPropsOnly) {
    if (!throng::vtk::displayAvailable()) GTEST_SKIP() << "no X display (run under xvfb-run)";
    auto scene = makeRandomCrowd(23, 400, 60.0);
    FrameContext context;
    context.time = 1.0;
    scene->crowd.step(context);

    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetSize(320, 240);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    auto culler = vtkSmartPointer<throng::vtk::CascadeCuller>::New();
    culler->SetScene(&scene->crowd, scene->root.get());
    renderer->GetCullers()->RemoveAllItems();
    renderer->AddCuller(culler);

    vtkNew<vtkCubeSource> box;
    box->SetBounds(-0.3, 0.3, 0.0, 1.8, -0.3, 0.3);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(box->GetOutputPort());
    std::vector<vtkSmartPointer<vtkActor>> props;
    for (ActorId id = 0; id < scene->crowd.size(); ++id) {
        props.push_back(vtkSmartPointer<vtkActor>::New());
        props.back()->SetMapper(mapper);
        renderer->AddActor(props.back());
        culler->SetActorProp(id, props.back());
    }
    vtkNew<vtkConeSource> coneSource;
    vtkNew<vtkPolyDataMapper> coneMapper;
    coneMapper->SetInputConnection(coneSource->GetOutputPort());
    vtkNew<vtkActor> cone;  // scenery in view: no actor's prop
    cone->SetMapper(coneMapper);
    cone->SetPosition(0, 1, 0);
    renderer->AddActor(cone);

    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(-20, 5, 0);
    camera->SetFocalPoint(10, 1, 5);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(50);
    camera->SetClippingRange(0.1, 500);

    for (int frame = 0; frame < 2; ++frame) {
        window->Render();
        // The props moved where the cascade found the actors (the application's part), then drawn again.
        for (ActorId id = 0; id < scene->crowd.size(); ++id) {
            const Mat4& r = scene->crowd.referencePoint(id);
            props[id]->SetPosition(r[3].x, r[3].y, r[3].z);
        }
        SCOPED_TRACE("frame " + std::to_string(frame));
        EXPECT_GT(culler->GetLastKept(), 0);
        EXPECT_GT(culler->GetLastRemoved(), 0);
        EXPECT_EQ(culler->GetLastKept() + culler->GetLastRemoved(), int(scene->crowd.size()));
        EXPECT_EQ(renderer->GetNumberOfPropsRendered(), culler->GetLastKept() + 1) << "the kept props and the cone";
    }
}
