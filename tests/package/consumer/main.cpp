// Builds a two-node scene with the installed Throng package, culls it and draws it headless with
// throng::render; exits 0 on success.
#include <cstdio>
#include <cstdlib>
#include <memory>

#include <throng/render/GlRenderer.h>
#include <throng/render/OsMesaContext.h>
#include <throng/render/ProceduralMeshes.h>
#include <throng/scenegraph/Camera.h>
#include <throng/scenegraph/Geometry.h>
#include <throng/scenegraph/MeshDrawable.h>
#include <throng/scenegraph/TraditionalProcessor.h>
#include <throng/scenegraph/Transform.h>

int main() {
    using namespace throng;
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
