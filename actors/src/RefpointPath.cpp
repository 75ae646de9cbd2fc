#include "throng/actors/RefpointPath.h"

#include <cmath>
#include <numbers>

namespace throng {

Mat4 RefpointPath::at(double time, OpTally* ops) const {
    Vec3 position = center;
    double yaw = heading;
    if (radius > 0.0) {
        const double theta = heading + (speed / radius) * time;
        position += Vec3(radius * std::sin(theta), 0.0, radius * std::cos(theta));
        yaw = theta + 0.5 * std::numbers::pi;  // tangent of the circle, counter-clockwise seen from +Y
        THRONG_TALLY(ops, 4, 4, 1, 2);
    }
    const double c = std::cos(yaw), s = std::sin(yaw);
    THRONG_TALLY(ops, 0, 0, 0, 2);
    Mat4 m(1.0);
    m[0] = Vec4(c, 0.0, -s, 0.0);  // rotation about +Y: local +Z goes to (sin yaw, 0, cos yaw)
    m[2] = Vec4(s, 0.0, c, 0.0);
    m[3] = Vec4(position, 1.0);
    return m;
}

}  // namespace throng
