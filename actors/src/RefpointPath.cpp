#include "throng/actors/RefpointPath.h"

#include <cmath>

namespace throng {

Mat4 RefpointPath::at(double time, OpTally* ops) const {
    Vec3 position = center;
    double c, s;  // cosine and sine of the yaw
    if (radius > 0.0) {
        // On the circle the actor faces along the tangent: yaw = theta + pi/2, so one sine and one
        // cosine serve both the position and the facing.
        const double theta = heading + (speed / radius) * time;
        const double sinT = std::sin(theta), cosT = std::cos(theta);
        position += Vec3(radius * sinT, 0.0, radius * cosT);
        c = -sinT;
        s = cosT;
        THRONG_TALLY(ops, 4, 4, 1, 2);
    } else {
        c = std::cos(heading);
        s = std::sin(heading);
        THRONG_TALLY(ops, 0, 0, 0, 2);
    }
    Mat4 m(1.0);
    m[0] = Vec4(c, 0.0, -s, 0.0);  // rotation about +Y: local +Z goes to (sin yaw, 0, cos yaw)
    m[2] = Vec4(s, 0.0, c, 0.0);
    m[3] = Vec4(position, 1.0);
    return m;
}

}  // namespace throng
