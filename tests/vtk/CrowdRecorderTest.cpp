// CrowdRecorder on a crowd built here: every file read back with VTK's readers, against what the
// test knows of the crowd (circle paths at a known speed, positions, cascade classes, the draw list).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include <vtkImageData.h>
#include <vtkPNGReader.h>
#include <vtkXMLImageDataReader.h>

#include "VtkFiles.h"
#include "throng/testkit/Cameras.h"
#include "throng/actors/Actor.h"
#include "throng/actors/ActorGroup.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"
#include "throng/scenegraph/Transform.h"
#include "throng/vtk/CrowdMaps.h"
#include "throng/vtk/CrowdRecorder.h"

using namespace throng;
using namespace throng::testkit;
namespace fs = std::filesystem;

namespace {

constexpr double kStep = 1.0 / 30.0;
constexpr double kSpeed = 1.4;    // m/s along each actor's circle
constexpr double kRadius = 5.0;   // m
constexpr int kActors = 30;
constexpr int kGrouped = 20;      // the first 20 in one group node, the others alone

fs::path freshFolder(const std::string& name) {
    const fs::path p = fs::path(THRONG_TEST_OUTPUT_DIR) / name;
    fs::remove_all(p);
    return p;
}

// What the test saw of one recorded step.
struct Seen {
    double time = 0;
    std::vector<Vec3> position;          // Reference Points
    std::vector<ActorClass> cls;         // cascade classes
    std::vector<int> drawn;              // items in the draw list per actor
    std::vector<double> eyeDistance;     // as the processor left it
};

struct World {
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    World() {
        const auto human = makeSeedHumanoid();
        auto walk = std::make_shared<KeyframeBehaviour>();
        std::vector<ActorId> grouped;
        for (int i = 0; i < kActors; ++i) {
            KeyframeBehaviour::Actor a;
            a.tmpl = human;
            a.clip = human->findClip("walk");
            a.position = Vec3(12.0 * i, 0.0, -30.0);  // a row: the far ones leave the view
            a.pathRadius = kRadius;
            a.pathSpeed = kSpeed;
            const ActorId id = crowd.add(human, walk, walk->addActor(a));
            if (i < kGrouped) grouped.push_back(id);
            else root->addChild(crowd.makeActorNode(id));
        }
        auto group = crowd.makeGroupNode(grouped);
        group->setName("walkers");
        root->addChild(group);
        // Static geometry: a box moved by a Transform, and an LOD whose coarse child must be left out.
        auto moved = std::make_shared<Transform>();
        moved->setMatrix(glm::translate(Mat4(1.0), Vec3(100.0, 0.0, 0.0)));
        moved->addChild(std::make_shared<Geometry>(std::make_shared<MeshDrawable>(makeBox("ground", glm::vec3(0), glm::vec3(1.0f)))));
        root->addChild(moved);
        auto lod = std::make_shared<LOD>();
        lod->addChild(std::make_shared<Geometry>(std::make_shared<MeshDrawable>(makeBox("fine", glm::vec3(0, 5, 0), glm::vec3(0.5f)))), 50.0);
        lod->addChild(std::make_shared<Geometry>(std::make_shared<MeshDrawable>(makeBox("coarse", glm::vec3(0, 50, 0), glm::vec3(9.0f)))), 500.0);
        root->addChild(lod);
    }
};

template <class Predicate>
std::size_t countIf(const std::vector<double>& v, Predicate p) { return std::size_t(std::count_if(v.begin(), v.end(), p)); }

Camera camera() {
    return testkit::lookingAt(Vec3(40.0, 3.0, 20.0), Vec3(40.0, 1.0, -30.0), {.fovY = 0.9});
}

}  // namespace

TEST(CrowdRecorder, FilesReadBackWithEveryActorAndAttribute) {
    World w;
    ActorProcessor processor(w.crowd);
    const fs::path dir = freshFolder("recorded");
    std::map<std::int64_t, Seen> seen;
    {
        throng::vtk::CrowdRecorder recorder(dir, 10);
        recorder.writeScene(*w.root);
        for (int step = 0; step < 25; ++step) {
            FrameContext context;
            context.time = step * kStep;
            context.deltaTime = step > 0 ? kStep : 0.0;
            context.frame = std::uint64_t(step);
            w.crowd.step(context);
            processor.processFrame(*w.root, camera(), context.time);
            recorder.record(w.crowd, processor);
            recorder.record(w.crowd, processor);  // the same step again (a paused window): ignored
            if (step % 10 != 0) continue;
            Seen& s = seen[step];
            s.time = context.time;
            s.drawn.assign(kActors, 0);
            for (const DrawItem& item : processor.drawList().items())
                if (item.actor != kNoActor) ++s.drawn[item.actor];
            for (ActorId a = 0; a < kActors; ++a) {
                s.position.push_back(Vec3(w.crowd.referencePoint(a)[3]));
                s.cls.push_back(w.crowd.actorClass(a));
                s.eyeDistance.push_back(w.crowd.eyeDistance(a));
            }
        }
        EXPECT_EQ(recorder.framesWritten(), 3u);
    }  // the destructor finishes: trajectories and the collection

    // The collection lists every frame written, with its time, and nothing else.
    const std::vector<PvdEntry> pvd = readPvd(dir / "crowd.pvd");
    ASSERT_EQ(pvd.size(), seen.size());
    std::size_t k = 0;
    bool someRejected = false, someDrawn = false;
    for (const auto& [step, s] : seen) {
        char name[64];
        std::snprintf(name, sizeof name, "actors_%06lld.vtp", (long long)step);
        EXPECT_EQ(pvd[k].file, name);
        EXPECT_DOUBLE_EQ(pvd[k].time, s.time);
        ++k;
        const auto data = readPolyData(dir / name);
        ASSERT_TRUE(data);
        ASSERT_EQ(data->GetNumberOfPoints(), kActors) << name;
        EXPECT_EQ(data->GetNumberOfVerts(), kActors) << name;
        EXPECT_DOUBLE_EQ(data->GetFieldData()->GetArray("TimeValue")->GetComponent(0, 0), s.time);
        const auto id = pointValues(*data, "id"), group = pointValues(*data, "group"), tmpl = pointValues(*data, "template");
        const auto tier = pointValues(*data, "tier"), lod = pointValues(*data, "lod"), level = pointValues(*data, "behaviour_level");
        const auto speed = pointValues(*data, "speed"), cls = pointValues(*data, "cascade_class"), rejected = pointValues(*data, "rejected_at");
        ASSERT_EQ(rejected.size(), std::size_t(kActors));
        for (int a = 0; a < kActors; ++a) {
            SCOPED_TRACE(std::string(name) + ", actor " + std::to_string(a));
            double p[3];
            data->GetPoint(a, p);
            EXPECT_EQ(Vec3(p[0], p[1], p[2]), s.position[std::size_t(a)]);
            EXPECT_EQ(id[std::size_t(a)], a);
            EXPECT_EQ(group[std::size_t(a)], a < kGrouped ? kActors - kGrouped : a - kGrouped) << "nodes in creation order: lone actors, then the group";
            EXPECT_EQ(tmpl[std::size_t(a)], 0);
            EXPECT_EQ(cls[std::size_t(a)], int(s.cls[std::size_t(a)]));
            // Circles at 1.4 m/s: the chord of one step, over the step (0 before the first step).
            if (step == 0) {
                EXPECT_EQ(speed[std::size_t(a)], 0.0);
            } else {
                EXPECT_NEAR(speed[std::size_t(a)], kSpeed, 1e-3);
            }
            const bool drawn = s.drawn[std::size_t(a)] > 0;
            someDrawn |= drawn;
            someRejected |= !drawn;
            EXPECT_EQ(tier[std::size_t(a)], drawn ? 0 : -1);  // no impostors or caches here: meshes
            EXPECT_EQ(rejected[std::size_t(a)] == 0, drawn);
            if (s.cls[std::size_t(a)] == ActorClass::A) {
                EXPECT_EQ(rejected[std::size_t(a)], 2);
            }
            if (s.cls[std::size_t(a)] == ActorClass::C1) {
                EXPECT_EQ(rejected[std::size_t(a)], 3);
            }
            if (drawn) {
                EXPECT_GE(lod[std::size_t(a)], 0);
                // KeyframeBehaviour's default bands: level 0 within 60 m, then 1.
                EXPECT_EQ(level[std::size_t(a)], s.eyeDistance[std::size_t(a)] < 60.0 ? 0 : 1);
            } else {
                EXPECT_EQ(lod[std::size_t(a)], -1);
                EXPECT_EQ(level[std::size_t(a)], -1);
            }
        }
        vtkAbstractArray* names = data->GetFieldData()->GetAbstractArray("group_names");
        ASSERT_NE(names, nullptr);
        EXPECT_EQ(names->GetVariantValue(names->GetNumberOfValues() - 1).ToString(), "walkers");
    }
    EXPECT_TRUE(someDrawn && someRejected) << "the camera should see some actors and not others";

    // Trajectories: one polyline per actor through its recorded positions, in order.
    const auto trajectories = readPolyData(dir / "trajectories.vtp");
    ASSERT_TRUE(trajectories);
    ASSERT_EQ(trajectories->GetNumberOfLines(), kActors);
    for (vtkIdType a = 0; a < kActors; ++a) {
        vtkCell* line = trajectories->GetCell(a);
        ASSERT_EQ(line->GetNumberOfPoints(), vtkIdType(seen.size()));
        std::size_t j = 0;
        for (const auto& [step, s] : seen) {
            double p[3];
            trajectories->GetPoint(line->GetPointId(vtkIdType(j++)), p);
            EXPECT_EQ(Vec3(p[0], p[1], p[2]), s.position[std::size_t(a)]) << "actor " << a << ", step " << step;
        }
    }

    // The crowd maps: every recorded actor-frame binned once, density in people per square metre.
    auto maps = vtkSmartPointer<vtkXMLImageDataReader>::New();
    ASSERT_TRUE(maps->CanReadFile((dir / "crowd_maps.vti").c_str()));
    maps->SetFileName((dir / "crowd_maps.vti").c_str());
    maps->Update();
    vtkImageData* image = maps->GetOutput();
    vtkDataArray* visits = image->GetPointData()->GetArray("visits");
    vtkDataArray* density = image->GetPointData()->GetArray("density");
    vtkDataArray* speed = image->GetPointData()->GetArray("speed");
    ASSERT_TRUE(visits && density && speed);
    const double cell = image->GetSpacing()[0];
    double visited = 0.0, people = 0.0, fastest = 0.0;
    for (vtkIdType c = 0; c < visits->GetNumberOfTuples(); ++c) {
        visited += visits->GetTuple1(c);
        people += density->GetTuple1(c) * cell * cell;
        fastest = std::max(fastest, speed->GetTuple1(c));
    }
    EXPECT_DOUBLE_EQ(visited, double(kActors * seen.size()));
    EXPECT_NEAR(people, double(kActors), 1e-9) << "on average every actor is somewhere in every recorded frame";
    EXPECT_GT(fastest, 0.5) << "the walkers move";
    // The fundamental diagram: every actor-frame (all on the ground here) in one row, by the people
    // sharing its cell then; its speeds sum to every recorded speed.
    const auto rows = throng::vtk::readSpeedDensity(dir / "speed_density.csv");
    ASSERT_FALSE(rows.empty());
    double actorFrames = 0.0, share = 0.0, speedSum = 0.0, recordedSpeeds = 0.0;
    for (const auto& r : rows) actorFrames += double(r.actorFrames), share += r.share, speedSum += r.meanSpeed * double(r.actorFrames);
    for (vtkIdType c = 0; c < visits->GetNumberOfTuples(); ++c) recordedSpeeds += speed->GetTuple1(c) * visits->GetTuple1(c);
    EXPECT_DOUBLE_EQ(actorFrames, double(kActors * seen.size()));
    EXPECT_NEAR(share, 1.0, 1e-6);
    EXPECT_NEAR(speedSum, recordedSpeeds, 1e-6 * recordedSpeeds);
    EXPECT_NEAR(rows.back().density, double(rows.back().people) / (cell * cell), 1e-9);
    for (const char* picture : {"density.png", "speed.png"}) {  // a square of pixels per cell, as VTK reads it back
        auto png = vtkSmartPointer<vtkPNGReader>::New();
        ASSERT_TRUE(png->CanReadFile((dir / picture).c_str())) << picture;
        png->SetFileName((dir / picture).c_str());
        png->Update();
        const int* size = png->GetOutput()->GetDimensions();
        const int scale = size[0] / image->GetDimensions()[0];
        EXPECT_GE(std::max(size[0], size[1]), 512) << picture;
        EXPECT_EQ(size[0], scale * image->GetDimensions()[0]) << picture;
        EXPECT_EQ(size[1], scale * image->GetDimensions()[1]) << picture;
        EXPECT_EQ(png->GetOutput()->GetNumberOfScalarComponents(), 4) << picture;
    }

    // The scene: the moved box and the LOD's finest child, no actor.
    const auto town = readPolyData(dir / "town.vtp");
    ASSERT_TRUE(town);
    EXPECT_EQ(town->GetNumberOfPolys(), 24);
    double bounds[6];
    town->GetBounds(bounds);
    EXPECT_DOUBLE_EQ(bounds[0], -0.5);  // the fine box
    EXPECT_DOUBLE_EQ(bounds[1], 101.0); // the moved box
    EXPECT_DOUBLE_EQ(bounds[3], 5.5);   // not the coarse box, 41 m higher
}

TEST(CrowdRecorder, BadArgumentsAreRefusedNamingTheProblem) {
    const fs::path dir = freshFolder("refused");
    fs::create_directories(dir);
    auto message = [](const fs::path& p, int every) {
        try {
            const throng::vtk::CrowdRecorder r(p, every);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(dir / "a", 0).find("at least 1"), std::string::npos) << message(dir / "a", 0);
    EXPECT_NE(message(dir / "a", -3).find("-3"), std::string::npos);
    std::ofstream(dir / "file") << "x";
    EXPECT_NE(message(dir / "file", 10).find("is not a folder"), std::string::npos) << message(dir / "file", 10);
    const std::string below = message(dir / "file" / "below", 10);
    EXPECT_NE(below.find("cannot create the folder"), std::string::npos) << below;
    EXPECT_NE(below.find((dir / "file" / "below").string()), std::string::npos) << below;
    EXPECT_EQ(message("", 10), "no folder given to record into");
    EXPECT_FALSE(fs::exists(dir / "a")) << "nothing is created for a bad interval";
}

TEST(CrowdRecorder, NothingRecordedStillGivesAnEmptyCollection) {
    const fs::path dir = freshFolder("empty");
    { throng::vtk::CrowdRecorder recorder(dir, 1); }
    EXPECT_TRUE(readPvd(dir / "crowd.pvd").empty());
    const auto trajectories = readPolyData(dir / "trajectories.vtp");
    ASSERT_TRUE(trajectories);
    EXPECT_EQ(trajectories->GetNumberOfLines(), 0);
}

TEST(CrowdRecorder, TraditionalProcessingClassifiesNobody) {
    World w;
    ActorProcessor processor(w.crowd);
    processor.setProcessing(Processing::Traditional);
    const fs::path dir = freshFolder("traditional");
    {
        throng::vtk::CrowdRecorder recorder(dir, 1);
        FrameContext context;
        w.crowd.step(context);
        processor.processFrame(*w.root, camera(), context.time);
        recorder.record(w.crowd, processor);
    }
    const auto data = readPolyData(dir / "actors_000000.vtp");
    ASSERT_TRUE(data);
    for (const char* array : {"cascade_class", "rejected_at"})
        for (double v : pointValues(*data, array)) EXPECT_EQ(v, -1.0) << array;
    const auto tier = pointValues(*data, "tier");
    EXPECT_GT(countIf(tier, [](double t) { return t == 0.0; }), 0u) << "traditional processing draws meshes too";
    // One frame: each trajectory is a line from its one position to itself.
    const auto trajectories = readPolyData(dir / "trajectories.vtp");
    ASSERT_TRUE(trajectories);
    ASSERT_EQ(trajectories->GetNumberOfLines(), kActors);
    vtkCell* line = trajectories->GetCell(3);
    ASSERT_EQ(line->GetNumberOfPoints(), 2);
    EXPECT_EQ(line->GetPointId(0), line->GetPointId(1));
    EXPECT_EQ(line->GetPointId(0), 3);
}
