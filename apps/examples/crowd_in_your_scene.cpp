// A crowd inside your own scenegraph: ordinary nodes (a floor, pillars under a Transform, a turning
// carousel driven by an update callback) and actors side by side in one tree. Actor groups can sit
// under any Group or Transform: the carousel's riders turn with it. One ActorProcessor traverses
// the whole tree: generic nodes get the usual APP, matrices and bounds, and CULL; actor nodes go
// through the cascade. The program prints the draw list's items of each kind for two cameras.
#include <cmath>
#include <cstdio>
#include <exception>

#include <glm/gtc/matrix_transform.hpp>

#include <throng/actors/ActorGroup.h>
#include <throng/actors/ActorProcessor.h>
#include <throng/actors/Crowd.h>
#include <throng/actors/KeyframeBehaviour.h>
#include <throng/actors/SeedHumanoid.h>
#include <throng/scenegraph/Camera.h>
#include <throng/scenegraph/DrawList.h>
#include <throng/scenegraph/Geometry.h>
#include <throng/scenegraph/Group.h>
#include <throng/scenegraph/MeshDrawable.h>
#include <throng/scenegraph/MeshShapes.h>
#include <throng/scenegraph/Transform.h>
#include <throng/scenegraph/UpdateCallback.h>

// Turns a Transform about +Y, one turn every `period` seconds: your own animation, run in APP.
class Turn : public throng::UpdateCallback {
public:
    explicit Turn(double period) : period_(period) {}
    void update(throng::Node& node, const throng::FrameContext& context) override {
        const double angle = 2.0 * 3.14159265358979 * context.time / period_;
        static_cast<throng::Transform&>(node).setMatrix(glm::rotate(throng::Mat4(1.0), angle, throng::Vec3(0, 1, 0)));
    }

private:
    double period_;
};

std::shared_ptr<throng::Geometry> shape(std::shared_ptr<throng::MeshData> mesh) {
    return std::make_shared<throng::Geometry>(std::make_shared<throng::MeshDrawable>(std::move(mesh)));
}

int main() try {
    // The crowd first: it must outlive every node that shows its actors (they release their actors
    // from it when destroyed), so it is declared before the scene and destroyed after it.
    const auto humanoid = throng::makeSeedHumanoid();
    auto walk = std::make_shared<throng::KeyframeBehaviour>();
    throng::Crowd crowd;

    auto root = std::make_shared<throng::Group>();
    root->addChild(shape(throng::makeBox("floor", {0, -0.05f, 0}, {40, 0.05f, 40})));
    for (int k = 0; k < 8; ++k) {  // pillars round the square, each placed by a Transform
        auto place = std::make_shared<throng::Transform>();
        place->setMatrix(glm::translate(throng::Mat4(1.0), throng::Vec3(30 * std::cos(k * 0.785), 0, 30 * std::sin(k * 0.785))));
        place->addChild(shape(throng::makeBox("pillar", {0, 3, 0}, {0.5f, 3, 0.5f})));
        root->addChild(place);
    }

    std::vector<throng::ActorId> strollers, riders;
    for (int i = 0; i < 200; ++i) {  // strollers walking circles on the square
        throng::KeyframeBehaviour::Actor a;
        a.tmpl = humanoid;
        a.clip = humanoid->findClip("walk");
        a.position = throng::Vec3(2.5 * (i % 20) - 25, 0, 2.5 * (i / 20) - 12);
        a.pathRadius = 1.0;
        a.pathSpeed = 1.3;
        strollers.push_back(crowd.add(humanoid, walk, walk->addActor(a)));
    }
    for (int i = 0; i < 12; ++i) {  // riders standing on the carousel: placed in its frame
        throng::KeyframeBehaviour::Actor a;
        a.tmpl = humanoid;
        a.clip = humanoid->findClip("walk");
        a.position = throng::Vec3(6 * std::cos(i * 0.5236), 0.5, 6 * std::sin(i * 0.5236));
        riders.push_back(crowd.add(humanoid, walk, walk->addActor(a)));
    }
    root->addChild(crowd.makeGroupNode(strollers));
    auto carousel = std::make_shared<throng::Transform>();
    carousel->setUpdateCallback(std::make_shared<Turn>(20.0));
    carousel->addChild(shape(throng::makeBox("carousel", {0, 0.25f, 0}, {7, 0.25f, 7})));
    carousel->addChild(crowd.makeGroupNode(riders));
    auto atCarousel = std::make_shared<throng::Transform>();
    atCarousel->setMatrix(glm::translate(throng::Mat4(1.0), throng::Vec3(0, 0, 20)));
    atCarousel->addChild(carousel);
    root->addChild(atCarousel);

    throng::ActorProcessor processor(crowd);
    std::uint64_t frame = 0;
    const throng::Vec3 eyes[2] = {{0, 1.7, -30}, {0, 40, 60}};
    const char* names[2] = {"street", "overview"};
    for (int c = 0; c < 2; ++c) {
        throng::Camera camera;
        camera.setPerspective(1.0, 16.0 / 9.0, 0.1, 300.0);
        camera.setLookAt(eyes[c], throng::Vec3(0, 0, 10), throng::Vec3(0, 1, 0));
        for (int k = 0; k < 30; ++k, ++frame) {  // a second of simulation per camera; the carousel turns in APP
            const throng::FrameContext context{double(frame) / 30.0, 1.0 / 30.0, frame, nullptr};
            crowd.step(context);
            processor.processFrame(*root, camera, context.time);
        }
        std::size_t actorItems = 0, otherItems = 0;
        for (const throng::DrawItem& item : processor.drawList().items()) (item.actor != throng::kNoActor ? actorItems : otherItems) += 1;
        const throng::ActorFrameStatistics& s = processor.statistics();
        std::printf("%s camera: %zu draw items of actors (%llu actors posed), %zu of your own nodes\n", names[c], actorItems,
                    (unsigned long long)s.actorsPosed, otherItems);
    }
    // The riders turned with the carousel: where the first rider stands now, in the world.
    const throng::Vec3 rider = throng::Vec3(crowd.referencePoint(riders[0])[3]);
    const double turned = std::atan2(rider.z - 20.0, rider.x) * 180.0 / 3.14159265358979;
    std::printf("first rider at (%.2f, %.2f, %.2f): carried %.1f degrees round the carousel's centre (0, 0, 20)\n", rider.x,
                rider.y, rider.z, turned);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
}
