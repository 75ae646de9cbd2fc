// Builds a two-node scene with the installed Throng package and culls it; exits 0 on success.
#include <cstdio>
#include <memory>

#include <throng/scenegraph/Camera.h>
#include <throng/scenegraph/Geometry.h>
#include <throng/scenegraph/TraditionalProcessor.h>
#include <throng/scenegraph/Transform.h>

int main() {
    using namespace throng;
    auto root = std::make_shared<Transform>();
    TransformDofs dofs;
    dofs.translation = Vec3(0, 0, -10);
    root->setDofs(dofs);
    root->addChild(std::make_shared<Geometry>(
        std::make_shared<Drawable>("box", BoundingSphere(Vec3(0.0), 1.0), 12)));
    Camera camera;
    TraditionalProcessor processor;
    processor.processFrame(*root, camera, 0.0);
    std::printf("consumer: %zu item(s) drawn\n", processor.drawList().size());
    return processor.drawList().size() == 1 ? 0 : 1;
}
