#include "throng/scenegraph/Frustum.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "throng/scenegraph/Validation.h"
#include "throng/scenegraph/detail/FrustumKernel.h"

namespace throng {

Frustum Frustum::fromViewProjection(const Mat4& m) {
    requireFinite(m, "Frustum::fromViewProjection", "viewProjection");
    auto row = [&m](int r) { return Vec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
    const Vec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
    const std::array<Vec4, kPlaneCount> raw = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};

    // A normal is negligible when it is tiny compared with the matrix entries that produced it.
    double scale = 0.0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) scale = std::max(scale, std::abs(m[c][r]));
    const double tiny = scale * 64.0 * std::numeric_limits<double>::epsilon();

    Frustum f;
    for (int i = 0; i < kPlaneCount; ++i) {
        const Vec3 n(raw[i]);
        const double len = glm::length(n);
        if (len <= tiny) {
            // No normal: the plane is at infinity (an infinite far plane), or the volume is empty.
            if (raw[i].w < 0.0)
                throw std::invalid_argument(
                    "Frustum::fromViewProjection: argument 'viewProjection' gives an empty volume "
                    "(plane " + std::to_string(i) + " has no normal and excludes every point)");
            f.planes_[i] = Vec4(0.0, 0.0, 0.0, 1.0);
            continue;
        }
        f.planes_[i] = raw[i] / len;
        f.active_ |= static_cast<PlaneMask>(1u << i);
    }
    return f;
}

Containment Frustum::classify(const BoundingSphere& s, PlaneMask& mask, OpTally* ops) const {
    return detail::classifySphere(planes_, s, mask, ops);
}

bool Frustum::contains(const Vec3& point) const {
    for (int i = 0; i < kPlaneCount; ++i) {
        if (!(active_ & (1u << i))) continue;
        const Vec4& p = planes_[i];
        if (p.x * point.x + p.y * point.y + p.z * point.z + p.w < 0.0) return false;
    }
    return true;
}

}  // namespace throng
