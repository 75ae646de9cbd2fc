#pragma once
// A camera: view and projection matrices, the eye position and the frustum they define.

#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/Math.h"

namespace throng {

/// View and projection of one viewpoint (OpenGL conventions, double precision).
class Camera {
public:
    /// Looks down -Z from the origin with a 60 degree vertical field of view, aspect 16:9, 0.1-1000 m.
    Camera();

    /// Sets a perspective projection. Throws std::invalid_argument unless 0 < fovY < pi,
    /// aspect > 0, 0 < near < far, all finite.
    void setPerspective(double fovYRadians, double aspect, double nearDistance, double farDistance);
    /// Places the eye at `eye` looking at `target` (the world is Y-up, as glTF). Throws std::invalid_argument if a value is not
    /// finite, eye == target, or `up` is parallel to the view direction.
    void setLookAt(const Vec3& eye, const Vec3& target, const Vec3& up = Vec3(0, 1, 0));
    /// Sets the view matrix directly (must be finite and invertible).
    void setViewMatrix(const Mat4& view);
    /// Sets the projection matrix directly (must be finite).
    void setProjectionMatrix(const Mat4& projection);

    /// World-to-eye matrix.
    const Mat4& view() const { return view_; }
    /// Eye-to-clip matrix.
    const Mat4& projection() const { return projection_; }
    /// projection() * view().
    Mat4 viewProjection() const { return projection_ * view_; }
    /// Eye position in world space.
    const Vec3& eye() const { return eye_; }
    /// Near distance of the last setPerspective (0 if the projection was set directly).
    double nearDistance() const { return near_; }
    /// Far distance of the last setPerspective (0 if the projection was set directly).
    double farDistance() const { return far_; }
    /// Vertical field of view of the last setPerspective, radians (0 if set directly).
    double fovY() const { return fovY_; }
    /// The world-space frustum.
    Frustum frustum() const { return Frustum::fromViewProjection(viewProjection()); }

private:
    Mat4 view_{1.0};
    Mat4 projection_{1.0};
    Vec3 eye_{0.0};
    double fovY_ = 0, near_ = 0, far_ = 0;
};

}  // namespace throng
