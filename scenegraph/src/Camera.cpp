#include "throng/scenegraph/Camera.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "throng/scenegraph/Validation.h"

namespace throng {

Camera::Camera() { setPerspective(std::numbers::pi / 3.0, 16.0 / 9.0, 0.1, 1000.0); view_ = glm::lookAt(Vec3(0.0), Vec3(0, 0, -1), Vec3(0, 1, 0)); }

void Camera::setPerspective(double fovY, double aspect, double nearDistance, double farDistance) {
    constexpr const char* where = "Camera::setPerspective";
    requireFinite(fovY, where, "fovYRadians");
    requireFinite(aspect, where, "aspect");
    requireFinite(nearDistance, where, "nearDistance");
    requireFinite(farDistance, where, "farDistance");
    if (!(fovY > 0.0 && fovY < std::numbers::pi))
        throw std::invalid_argument(std::string(where) + ": argument 'fovYRadians' must be in (0, pi), got " + std::to_string(fovY));
    if (!(aspect > 0.0))
        throw std::invalid_argument(std::string(where) + ": argument 'aspect' must be positive, got " + std::to_string(aspect));
    if (!(nearDistance > 0.0))
        throw std::invalid_argument(std::string(where) + ": argument 'nearDistance' must be positive, got " + std::to_string(nearDistance));
    if (!(farDistance > nearDistance))
        throw std::invalid_argument(std::string(where) + ": argument 'farDistance' must exceed nearDistance, got " + std::to_string(farDistance));
    projection_ = glm::perspective(fovY, aspect, nearDistance, farDistance);
    fovY_ = fovY;
    near_ = nearDistance;
    far_ = farDistance;
}

void Camera::setLookAt(const Vec3& eye, const Vec3& target, const Vec3& up) {
    constexpr const char* where = "Camera::setLookAt";
    requireFinite(eye, where, "eye");
    requireFinite(target, where, "target");
    requireFinite(up, where, "up");
    const Vec3 dir = target - eye;
    const double len = glm::length(dir);
    if (!(len > 0.0)) throw std::invalid_argument(std::string(where) + ": arguments 'eye' and 'target' coincide");
    const double upLen = glm::length(up);
    if (!(upLen > 0.0) || glm::length(glm::cross(dir / len, up / upLen)) < 1e-9)
        throw std::invalid_argument(std::string(where) + ": argument 'up' is zero or parallel to the view direction");
    view_ = glm::lookAt(eye, target, up);
    eye_ = eye;
}

void Camera::setViewMatrix(const Mat4& view) {
    requireFinite(view, "Camera::setViewMatrix", "view");
    const double det = glm::determinant(view);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det))
        throw std::invalid_argument("Camera::setViewMatrix: argument 'view' is not invertible");
    view_ = view;
    eye_ = Vec3(glm::inverse(view)[3]);
}

void Camera::setProjectionMatrix(const Mat4& projection) {
    requireFinite(projection, "Camera::setProjectionMatrix", "projection");
    projection_ = projection;
    fovY_ = near_ = far_ = 0.0;
}

}  // namespace throng
