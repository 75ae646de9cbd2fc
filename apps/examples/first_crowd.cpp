// A first crowd: a glTF character cloned 500 times, each walking its own circle, processed by the
// actor cascade for a camera standing among them. Prints, every 20 frames, where the actors left
// the cascade. Usage: throng-example-first-crowd [character.glb] (default: CesiumMan).
#include <cstdio>
#include <exception>

#include <throng/actors/ActorGroup.h>
#include <throng/actors/ActorProcessor.h>
#include <throng/actors/Crowd.h>
#include <throng/actors/KeyframeBehaviour.h>
#include <throng/gltf/GltfLoader.h>
#include <throng/scenegraph/Camera.h>
#include <throng/scenegraph/Group.h>

int main(int argc, char** argv) try {
    const char* file = argc > 1 ? argv[1] : "../shared/assets/characters/CesiumMan.glb";
    const throng::CharacterAsset asset = throng::loadCharacter(file);
    const auto character = asset.primaryTemplate();            // joints, skin, clips, spheres
    auto walk = std::make_shared<throng::KeyframeBehaviour>();  // plays a clip along a path
    throng::Crowd crowd;                                        // every actor's state, flat arrays
    std::vector<throng::ActorId> ids;
    for (int i = 0; i < 500; ++i) {
        throng::KeyframeBehaviour::Actor a;
        a.tmpl = character;
        a.clip = 0;  // the file's first animation
        a.position = throng::Vec3(4.0 * (i % 25) - 48.0, 0.0, 4.0 * (i / 25) - 38.0);
        a.pathRadius = 1.5;  // the Reference Point walks a circle round `position`
        a.pathSpeed = 1.2;
        a.heading = 0.37 * i;
        ids.push_back(crowd.add(character, walk, walk->addActor(a)));
    }
    auto scene = std::make_shared<throng::Group>();
    scene->addChild(crowd.makeGroupNode(ids));  // one node: culled as one sphere first

    throng::Camera camera;
    camera.setPerspective(1.0, 16.0 / 9.0, 0.1, 300.0);
    camera.setLookAt(throng::Vec3(0, 1.7, -45), throng::Vec3(10, 1, 0), throng::Vec3(0, 1, 0));
    throng::ActorProcessor processor(crowd);  // the seven-phase cascade
    for (std::uint64_t frame = 0; frame < 60; ++frame) {
        const throng::FrameContext context{frame / 30.0, 1.0 / 30.0, frame, nullptr};
        crowd.step(context);  // the simulation first, once a frame
        const throng::ActorFrameStatistics& s = processor.processFrame(*scene, camera, context.time);
        if (frame % 20 == 0)
            std::printf("frame %2llu: %llu actors, %llu rejected by CULL 1, %llu by CULL 2, %llu posed, "
                        "%llu draw items\n",
                        (unsigned long long)frame, (unsigned long long)s.actorsInScene,
                        (unsigned long long)s.a, (unsigned long long)s.c1,
                        (unsigned long long)s.actorsPosed, (unsigned long long)s.drawItems);
    }
    return 0;
} catch (const std::exception& e) {  // a file that cannot load: one line naming it and where
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
}
