#include "throng/testkit/Cameras.h"

namespace throng::testkit {

Camera lookingAt(const Vec3& eye, const Vec3& target, const Lens& lens) {
    Camera camera;
    camera.setPerspective(lens.fovY, lens.aspect, lens.near, lens.far);
    camera.setLookAt(eye, target, Vec3(0, 1, 0));
    return camera;
}

}  // namespace throng::testkit
