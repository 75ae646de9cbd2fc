// CrowdProp in a real render (under a virtual X display: xvfb-run): the cascade's counts for VTK's
// camera equal Throng's own ActorProcessor on a twin crowd, actors show up in the picture, and an
// ordinary VTK cone placed in front of an actor hides it (one depth buffer).

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkConeSource.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/actors/Actor.h"
#include "throng/actors/ActorGroup.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/vtk/Chart.h"
#include "throng/vtk/CrowdProp.h"

using namespace throng;

namespace {

constexpr int kWidth = 320, kHeight = 240;

// A row of red humanoids along x at z = -10, standing (no path), with some far to the sides.
struct Row {
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    Row() {
        const auto human = makeSeedHumanoid();
        auto stand = std::make_shared<KeyframeBehaviour>();
        std::vector<ActorId> ids;
        for (int i = 0; i < 24; ++i) {
            KeyframeBehaviour::Actor a;
            a.tmpl = human;
            a.clip = human->findClip("walk");
            a.position = Vec3(-60.0 + 5.0 * i, 0.0, -10.0);
            ids.push_back(crowd.add(human, stand, stand->addActor(a), ActorLook{1.0f, glm::vec4(1, 0, 0, 1), {}}));
        }
        root->addChild(crowd.makeGroupNode(ids));
    }
};

struct Picture {
    std::vector<unsigned char> rgb;
    const unsigned char* at(int x, int y) const { return &rgb[std::size_t(y * kWidth + x) * 3]; }
};

// Renders `window`, keeps the picture in the test's output folder as `name`, and returns it.
Picture grab(vtkRenderWindow& window, const std::string& name) {
    window.Render();
    vtkNew<vtkWindowToImageFilter> grabber;
    grabber->SetInput(&window);
    grabber->ReadFrontBufferOff();
    grabber->Update();
    std::filesystem::create_directories(THRONG_TEST_OUTPUT_DIR);
    vtkNew<vtkPNGWriter> png;
    png->SetInputConnection(grabber->GetOutputPort());
    png->SetFileName((std::filesystem::path(THRONG_TEST_OUTPUT_DIR) / name).c_str());
    png->Write();
    auto* scalars = vtkUnsignedCharArray::SafeDownCast(grabber->GetOutput()->GetPointData()->GetScalars());
    Picture p;
    const int components = scalars->GetNumberOfComponents();
    for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
        for (int c = 0; c < 3; ++c) p.rgb.push_back(scalars->GetTypedComponent(i, c * (components >= 3 ? 1 : 0)));
    return p;
}

// The actors are tinted red: every material keeps only its red channel (at least 0.25 of it).
bool red(const unsigned char* p) { return p[0] > 40 && p[1] < 16 && p[2] < 16; }
bool green(const unsigned char* p) { return p[1] > 128 && p[0] < 64 && p[2] < 64; }

}  // namespace

// Drawn through the VTK mapper (false) and by Throng's own renderer in VTK's context (true).
class CrowdPropDrawing : public ::testing::TestWithParam<bool> {};

TEST_P(CrowdPropDrawing, CascadeCountsMatchAndTheConeHidesTheActorBehindIt) {
    if (!throng::vtk::displayAvailable()) GTEST_SKIP() << "no X display (run under xvfb-run)";
    const bool throngDrawing = GetParam();
    const std::string prefix = throngDrawing ? "throng-" : "";
    Row seen, twin;
    FrameContext context;
    context.time = 0.5;
    seen.crowd.step(context);
    twin.crowd.step(context);

    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetSize(kWidth, kHeight);
    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(0, 0, 0);
    window->AddRenderer(renderer);
    auto crowdProp = vtkSmartPointer<throng::vtk::CrowdProp>::New();
    crowdProp->SetScene(&seen.crowd, seen.root.get());
    crowdProp->GetActorProperty()->LightingOff();  // flat colours: red actors (Throng's light keeps them red)
    crowdProp->SetThrongDrawing(throngDrawing);
    renderer->AddViewProp(crowdProp);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0, 1, 0);
    camera->SetFocalPoint(0, 1, -10);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(60);
    camera->SetClippingRange(0.1, 100);

    const Picture before = grab(*window, prefix + "crowd-prop.png");
    // The same camera given to Throng directly, on the twin crowd: the same cascade.
    Camera throngCamera;
    throngCamera.setPerspective(60.0 * std::numbers::pi / 180.0, double(kWidth) / kHeight, 0.1, 100.0);
    throngCamera.setLookAt(Vec3(0, 1, 0), Vec3(0, 1, -10));
    ActorProcessor processor(twin.crowd);
    const ActorFrameStatistics expected = processor.processFrame(*twin.root, throngCamera, context.time);
    const ActorFrameStatistics& got = crowdProp->GetLastStatistics();
    EXPECT_EQ(got.a, expected.a);
    EXPECT_EQ(got.b, expected.b);
    EXPECT_EQ(got.c1, expected.c1);
    EXPECT_EQ(got.c2, expected.c2);
    EXPECT_EQ(got.c3_1, expected.c3_1);
    EXPECT_EQ(got.c3_2, expected.c3_2);
    EXPECT_EQ(got.drawItems, expected.drawItems);
    EXPECT_GT(got.a + got.c1, 0u) << "some actors are outside the view";
    EXPECT_GT(crowdProp->GetLastTriangles(), 0u);

    // The actor at x = 0 stands in the middle of the picture, in front of the black background.
    const int cx = kWidth / 2, cy = kHeight / 2;
    ASSERT_TRUE(red(before.at(cx, cy))) << "the middle actor is drawn: " << int(before.at(cx, cy)[0]) << " "
                                        << int(before.at(cx, cy)[1]) << " " << int(before.at(cx, cy)[2]);
    std::size_t redBefore = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) redBefore += red(before.at(x, y));

    // A green cone between the camera and that actor hides it; the actors beside it stay visible.
    vtkNew<vtkConeSource> coneSource;
    coneSource->SetHeight(1.0);
    coneSource->SetRadius(0.6);
    coneSource->SetResolution(32);
    coneSource->SetDirection(0, 1, 0);
    vtkNew<vtkPolyDataMapper> coneMapper;
    coneMapper->SetInputConnection(coneSource->GetOutputPort());
    vtkNew<vtkActor> cone;
    cone->SetMapper(coneMapper);
    cone->GetProperty()->SetColor(0, 1, 0);
    cone->GetProperty()->LightingOff();
    cone->SetPosition(0, 1, -5);
    renderer->AddActor(cone);
    const Picture after = grab(*window, prefix + "crowd-prop-cone-in-front.png");
    EXPECT_TRUE(green(after.at(cx, cy))) << "the cone, nearer, hides the actor behind it";
    std::size_t redAfter = 0, greenAfter = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) redAfter += red(after.at(x, y)), greenAfter += green(after.at(x, y));
    EXPECT_GT(greenAfter, 0u);
    EXPECT_LT(redAfter, redBefore) << "red pixels behind the cone are gone";
    EXPECT_GT(redAfter, redBefore / 2) << "the other actors are still drawn";

    // Behind the actors the cone is hidden by them instead.
    cone->SetPosition(0, 1, -20);
    const Picture behind = grab(*window, prefix + "crowd-prop-cone-behind.png");
    EXPECT_TRUE(red(behind.at(cx, cy))) << "the actor, nearer, hides the cone";
    if (throngDrawing) {
        ASSERT_NE(crowdProp->GetLastRenderStatistics(), nullptr);
        EXPECT_EQ(crowdProp->GetLastRenderStatistics()->meshes.instances, got.drawItems) << "Throng's renderer drew every item";
        // VTK's own props still draw right after the crowd (its GL state was given back): the cone
        // moved in front again shows.
        cone->SetPosition(0, 1, -5);
        const Picture again = grab(*window, prefix + "crowd-prop-cone-again.png");
        EXPECT_TRUE(green(again.at(cx, cy)));
    }
}

INSTANTIATE_TEST_SUITE_P(CrowdPropRender, CrowdPropDrawing, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "ThrongRenderer" : "VtkMapper"; });

TEST(CrowdPropRender, SkinnedMeshesAreBlendedByTheirPalette) {
    if (!throng::vtk::displayAvailable()) GTEST_SKIP() << "no X display (run under xvfb-run)";
    // A 2 m bar skinned to two joints; its upper joint (1 m up) turns 90 degrees about Z in the
    // first second of "bend": the top vertices go from (+-0.05, 2) to (-1, 1 +- 0.05).
    Crowd crowd;
    auto root = std::make_shared<Group>();
    const auto bar = throng::testkit::skinnedBar();
    auto play = std::make_shared<KeyframeBehaviour>();
    KeyframeBehaviour::Actor a;
    a.tmpl = bar;
    root->addChild(crowd.makeActorNode(crowd.add(bar, play, play->addActor(a))));

    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetSize(kWidth, kHeight);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    auto crowdProp = vtkSmartPointer<throng::vtk::CrowdProp>::New();
    crowdProp->SetScene(&crowd, root.get());
    renderer->AddViewProp(crowdProp);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0, 1, 6);
    camera->SetFocalPoint(0, 1, 0);
    camera->SetClippingRange(0.1, 100);
    for (const double time : {0.0, 1.5}) {
        FrameContext context;
        context.time = time;
        crowd.step(context);
        window->Render();
        double b[6];
        crowdProp->GetLastMeshes()->GetBounds(b);
        SCOPED_TRACE("time " + std::to_string(time));
        EXPECT_EQ(crowdProp->GetLastMeshes()->GetNumberOfPolys(), 12);
        EXPECT_NEAR(b[0], time == 0.0 ? -0.05 : -1.0, 1e-4);
        EXPECT_NEAR(b[1], 0.05, 1e-4);
        EXPECT_NEAR(b[2], 0.0, 1e-4);
        EXPECT_NEAR(b[3], time == 0.0 ? 2.0 : 1.05, 1e-4);
    }
}
