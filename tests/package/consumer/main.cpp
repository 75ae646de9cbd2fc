// Builds a two-node scene with the installed Throng package, culls it and draws it headless with
// throng::render, and loads a one-triangle glTF document with throng::gltf; exits 0 on success.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <throng/actors/ActorGroup.h>
#include <throng/actors/ActorProcessor.h>
#include <throng/actors/Crowd.h>
#include <throng/actors/KeyframeBehaviour.h>
#include <throng/actors/SeedHumanoid.h>
#include <throng/gltf/GltfLoader.h>
#include <throng/render/GlRenderer.h>
#include <throng/render/OsMesaContext.h>
#include <throng/render/ProceduralMeshes.h>
#include <throng/scenegraph/Camera.h>
#include <throng/scenegraph/Geometry.h>
#include <throng/scenegraph/MeshDrawable.h>
#include <throng/scenegraph/TraditionalProcessor.h>
#include <throng/scenegraph/Transform.h>

namespace {

// throng::gltf from the package: a glTF document in memory (one triangle, its buffer a data URI)
// becomes one rigid template drawing one triangle.
bool loadsGltf() {
    const std::string json =
        R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
        R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}]})";
    const throng::CharacterAsset asset = throng::loadCharacterFromMemory(std::vector<std::uint8_t>(json.begin(), json.end()), "triangle.gltf");
    std::printf("consumer: glTF loaded, %zu template(s), %zu primitive(s)\n", asset.characters.size(), asset.primitives.size());
    return asset.primaryTemplate() && asset.primitives.size() == 1 && asset.primitives[0].data->triangleCount() == 1;
}

// throng::actors from the package (which must need no GLPK): ten humanoids through the cascade.
bool processesActors() {
    const auto humanoid = throng::makeSeedHumanoid();
    auto stand = std::make_shared<throng::KeyframeBehaviour>();
    throng::Crowd crowd;
    std::vector<throng::ActorId> ids;
    for (int i = 0; i < 10; ++i) {
        throng::KeyframeBehaviour::Actor a;
        a.tmpl = humanoid;
        a.position = throng::Vec3(i - 5.0, 0.0, -10.0);
        ids.push_back(crowd.add(humanoid, stand, stand->addActor(a)));
    }
    auto scene = std::make_shared<throng::Group>();
    scene->addChild(crowd.makeGroupNode(ids));
    throng::ActorProcessor processor(crowd);
    const throng::FrameContext context{0.0, 0.0, 0, nullptr};
    crowd.step(context);
    const throng::ActorFrameStatistics& s = processor.processFrame(*scene, throng::Camera(), context.time);
    std::printf("consumer: %llu actors posed by the cascade\n", static_cast<unsigned long long>(s.actorsPosed));
    return s.actorsPosed == 10;
}

}  // namespace

int main() {
    using namespace throng;
    if (!loadsGltf() || !processesActors()) return 1;
    auto root = std::make_shared<Transform>();
    TransformDofs dofs;
    dofs.translation = Vec3(0, 0, -10);
    root->setDofs(dofs);
    root->addChild(std::make_shared<Geometry>(std::make_shared<MeshDrawable>(makeBox("box", glm::vec3(0.0f), glm::vec3(1.0f)))));
    Camera camera;
    TraditionalProcessor processor;
    processor.processFrame(*root, camera, 0.0);
    std::printf("consumer: %zu item(s) culled in\n", processor.drawList().size());
    if (processor.drawList().size() != 1) return 1;

    GlRenderer renderer(std::make_shared<OsMesaContext>(64, 36));
    processor.processFrame(*root, camera, 0.0, &renderer);
    const Image frame = renderer.readFrame();
    const std::uint8_t* centre = &frame.rgba[(static_cast<std::size_t>(frame.height / 2) * frame.width + frame.width / 2) * 4];
    std::printf("consumer: %llu triangle(s) drawn by %s, centre pixel %d %d %d\n",
                static_cast<unsigned long long>(renderer.statistics().triangles), renderer.context().description().c_str(),
                centre[0], centre[1], centre[2]);
    const int clearRed = static_cast<int>(renderer.options().clearColor.r * 255.0f + 0.5f);
    const bool boxAtCentre = std::abs(centre[0] - clearRed) > 30;  // the white box, not the background
    return renderer.statistics().triangles == 12 && boxAtCentre ? 0 : 1;
}
