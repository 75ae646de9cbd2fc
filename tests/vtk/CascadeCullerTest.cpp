// CascadeCuller: the props it removes are exactly those of the actors Throng's own ActorProcessor
// rejects (with their group, CULL 1, CULL 2) for the same camera, built independently on a twin
// crowd; and every removal is confirmed by VTK's own frustum planes.

#include <gtest/gtest.h>

#include <random>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/vtk/CameraFromVtk.h"
#include "throng/vtk/CascadeCuller.h"

using namespace throng;
using namespace throng::testkit;

namespace {

constexpr int kActors = 1500;
constexpr double kExtent = 150.0;

// A camera given the same way to VTK and to Throng.
struct View {
    Vec3 eye, target, up{0, 1, 0};
    double fovDegrees = 50.0, nearDistance = 0.1, farDistance = 2000.0;
};

bool rejected(ActorClass c) {
    return c == ActorClass::A || c == ActorClass::C1 || c == ActorClass::CulledWithGroup || c == ActorClass::Occluded ||
           c == ActorClass::NotInScene;
}

// Signed distances of `sphere` to VTK's frustum planes (inward normals): outside when any is below -radius.
bool outsideVtkPlanes(const double planes[24], const Vec3& center, double radius) {
    for (int p = 0; p < 6; ++p) {
        const double* q = planes + 4 * p;
        const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        if ((q[0] * center.x + q[1] * center.y + q[2] * center.z + q[3]) / n < -radius * (1.0 + 1e-9) - 1e-9) return true;
    }
    return false;
}

}  // namespace

TEST(CascadeCuller, RemovesExactlyThePropsOfTheActorsTheCascadeRejects) {
    auto seen = makeRandomCrowd(17, kActors, kExtent);       // culled through VTK
    auto reference = makeRandomCrowd(17, kActors, kExtent);  // its twin, processed by Throng alone
    seen->vehicle->setMatrix(glm::translate(Mat4(1.0), Vec3(3.0 * kExtent, 0.0, 0.0)));
    reference->vehicle->setMatrix(glm::translate(Mat4(1.0), Vec3(3.0 * kExtent, 0.0, 0.0)));

    vtkNew<vtkRenderWindow> window;  // never rendered: it gives the renderer its aspect ratio
    window->SetSize(900, 600);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    auto culler = vtkSmartPointer<throng::vtk::CascadeCuller>::New();
    culler->SetScene(&seen->crowd, seen->root.get());
    std::vector<vtkSmartPointer<vtkActor>> props;
    for (ActorId id = 0; id < kActors; ++id) {
        props.push_back(vtkSmartPointer<vtkActor>::New());
        culler->SetActorProp(id, props.back());
    }
    vtkNew<vtkActor> scenery;  // stands for no actor: left to the other cullers

    ActorProcessor processor(reference->crowd);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<View> views = {
        {Vec3(0, 60, 250), Vec3(0, 0, 0)},                        // overview
        {Vec3(0, 1.7, 0), Vec3(40, 1.5, 10)},                     // inside the crowd
        {Vec3(-200, 2, 0), Vec3(0, 2, 0), Vec3(0, 1, 0), 10.0},   // narrow
        {Vec3(0, 2, 0), Vec3(0, 2, -50), Vec3(0, 1, 0), 120.0},   // wide
        {Vec3(420, 5, 30), Vec3(450, 0, 0)},                      // at the vehicle
        {Vec3(0, 300, 1), Vec3(0, 0, 0), Vec3(0, 0, -1), 30.0, 1.0, 280.0},  // from above, short far plane
    };
    for (int i = 0; i < 8; ++i) views.push_back({Vec3(kExtent * u(rng), 2 + 20 * (1 + u(rng)), kExtent * u(rng)), Vec3(kExtent * u(rng), 0, kExtent * u(rng))});

    std::size_t kept = 0, removed = 0, byGroup = 0, byCull1 = 0, byCull2 = 0;
    for (std::size_t v = 0; v < views.size(); ++v) {
        SCOPED_TRACE("view " + std::to_string(v));
        const View& view = views[v];
        FrameContext context;
        context.time = 0.5 * double(v);
        context.frame = v;
        seen->crowd.step(context);
        reference->crowd.step(context);

        vtkCamera* camera = renderer->GetActiveCamera();
        camera->SetPosition(view.eye.x, view.eye.y, view.eye.z);
        camera->SetFocalPoint(view.target.x, view.target.y, view.target.z);
        camera->SetViewUp(view.up.x, view.up.y, view.up.z);
        camera->SetViewAngle(view.fovDegrees);
        camera->SetClippingRange(view.nearDistance, view.farDistance);
        std::vector<vtkProp*> list;
        for (auto& p : props) list.push_back(p);
        list.insert(list.begin() + 100, scenery);
        int count = int(list.size()), initialized = 0;
        culler->Cull(renderer, list.data(), count, initialized);
        list.resize(std::size_t(count));

        Camera throngCamera;
        throngCamera.setPerspective(view.fovDegrees * std::numbers::pi / 180.0, 1.5, view.nearDistance, view.farDistance);
        throngCamera.setLookAt(view.eye, view.target, view.up);
        processor.processFrame(*reference->root, throngCamera, context.time);

        double planes[24];
        camera->GetFrustumPlanes(renderer->GetTiledAspectRatio(), planes);
        std::vector<bool> inList(kActors, false);
        bool sceneryKept = false;
        for (vtkProp* p : list) {
            if (p == scenery.Get()) sceneryKept = true;
            for (ActorId id = 0; id < kActors; ++id)
                if (props[id].Get() == p) inList[id] = true;
        }
        EXPECT_TRUE(sceneryKept) << "a prop that stands for no actor is not the cascade's to remove";
        for (ActorId id = 0; id < kActors; ++id) {
            const ActorClass expected = reference->crowd.actorClass(id);
            EXPECT_EQ(seen->crowd.actorClass(id), expected) << "actor " << id;
            EXPECT_EQ(inList[id], !rejected(expected)) << "actor " << id << " class " << int(expected);
            (inList[id] ? kept : removed) += 1;
            // VTK's own planes confirm each removal, and never see a kept actor's Refpoint Bsphere outside.
            const BoundingSphere& ref = seen->crowd.refpointSphere(id);
            if (expected == ActorClass::A || expected == ActorClass::CulledWithGroup) {
                EXPECT_TRUE(outsideVtkPlanes(planes, ref.center(), ref.radius())) << "actor " << id;
            } else if (expected == ActorClass::C1) {
                EXPECT_TRUE(outsideVtkPlanes(planes, Vec3(seen->crowd.skeletonRoot(id)[3]), seen->crowd.skeletonRootRadius(id))) << "actor " << id;
            } else {
                EXPECT_FALSE(outsideVtkPlanes(planes, ref.center(), ref.radius())) << "actor " << id;
            }
            byGroup += expected == ActorClass::CulledWithGroup, byCull1 += expected == ActorClass::A, byCull2 += expected == ActorClass::C1;
        }
        EXPECT_EQ(culler->GetLastKept() + culler->GetLastRemoved(), kActors);
        EXPECT_EQ(std::size_t(culler->GetLastRemoved()), std::size_t(std::count_if(inList.begin(), inList.end(), [](bool b) { return !b; })));
    }
    // The views exercise every way out of the cascade.
    EXPECT_GT(kept, 0u);
    EXPECT_GT(byGroup, 0u);
    EXPECT_GT(byCull1, 0u);
    EXPECT_GT(byCull2, 0u);
}

TEST(CascadeCuller, CameraFromVtkMatchesThrongsOwnCamera) {
    vtkNew<vtkCamera> camera;
    camera->SetPosition(3, 4, 5);
    camera->SetFocalPoint(-2, 1, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(40.0);
    camera->SetClippingRange(0.5, 900.0);
    const Camera fromVtk = throng::vtk::cameraFromVtk(*camera, 1.6);
    Camera own;
    own.setPerspective(40.0 * std::numbers::pi / 180.0, 1.6, 0.5, 900.0);
    own.setLookAt(Vec3(3, 4, 5), Vec3(-2, 1, 0));
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(fromVtk.view()[c][r], own.view()[c][r], 1e-12) << c << "," << r;
            EXPECT_NEAR(fromVtk.projection()[c][r], own.projection()[c][r], 1e-12) << c << "," << r;
        }
    EXPECT_NEAR(glm::distance(fromVtk.eye(), Vec3(3, 4, 5)), 0.0, 1e-12);
    EXPECT_THROW(throng::vtk::cameraFromVtk(*camera, 0.0), std::invalid_argument);
}

TEST(CascadeCuller, BadUseIsRefusedNamingTheProblem) {
    auto culler = vtkSmartPointer<throng::vtk::CascadeCuller>::New();
    EXPECT_THROW(culler->SetActorProp(0, nullptr), std::invalid_argument);
    EXPECT_THROW(culler->SetScene(nullptr, nullptr), std::invalid_argument);
    auto scene = makeRandomCrowd(3, 10, 20.0);
    culler->SetScene(&scene->crowd, scene->root.get());
    vtkNew<vtkActor> prop;
    try {
        culler->SetActorProp(10, prop);
        ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("actor 10 is not in the crowd (10 actors)"), std::string::npos) << e.what();
    }
    // Without a renderer or props the culler leaves the list alone.
    int count = 0, initialized = 0;
    EXPECT_EQ(culler->Cull(nullptr, nullptr, count, initialized), 0.0);
}
