#include "throng/scenegraph/SphereArrayCuller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace throng {
namespace {

// Relative rounding of float coordinates and of the dot product (a few ulps of each magnitude).
constexpr float kRelMargin = 8.0f * std::numeric_limits<float>::epsilon();

// The kernel is compiled for several instruction sets and chosen at load time. Its body has no
// branch: per sphere, the smallest "distance + reach" over the planes says whether it is outside
// one, the smallest "distance - reach" whether it is inside all, so it vectorises across spheres.
__attribute__((target_clones("avx512f", "avx2", "default")))
void classifyKernel(const float* __restrict x, const float* __restrict y, const float* __restrict z,
                    const float* __restrict radius, std::size_t n, const float* __restrict nx,
                    const float* __restrict ny, const float* __restrict nz, const float* __restrict d,
                    const float* __restrict dMargin, std::uint8_t* __restrict out) {
    const float nx0 = nx[0], nx1 = nx[1], nx2 = nx[2], nx3 = nx[3], nx4 = nx[4], nx5 = nx[5];
    const float ny0 = ny[0], ny1 = ny[1], ny2 = ny[2], ny3 = ny[3], ny4 = ny[4], ny5 = ny[5];
    const float nz0 = nz[0], nz1 = nz[1], nz2 = nz[2], nz3 = nz[3], nz4 = nz[4], nz5 = nz[5];
    const float d0 = d[0], d1 = d[1], d2 = d[2], d3 = d[3], d4 = d[4], d5 = d[5];
    const float m0 = dMargin[0], m1 = dMargin[1], m2 = dMargin[2], m3 = dMargin[3], m4 = dMargin[4],
                m5 = dMargin[5];
    for (std::size_t i = 0; i < n; ++i) {
        const float cx = x[i], cy = y[i], cz = z[i];
        const float reach = radius[i] + kRelMargin * (std::fabs(cx) + std::fabs(cy) + std::fabs(cz) + radius[i]);
        const float s0 = nx0 * cx + ny0 * cy + nz0 * cz + d0, s1 = nx1 * cx + ny1 * cy + nz1 * cz + d1;
        const float s2 = nx2 * cx + ny2 * cy + nz2 * cz + d2, s3 = nx3 * cx + ny3 * cy + nz3 * cz + d3;
        const float s4 = nx4 * cx + ny4 * cy + nz4 * cz + d4, s5 = nx5 * cx + ny5 * cy + nz5 * cz + d5;
        // Lowest clearance over the planes, once widened by the reach (outside test) and once
        // narrowed by it (inside test).
        const float lowOut = std::min(std::min(std::min(s0 + m0, s1 + m1), std::min(s2 + m2, s3 + m3)),
                                      std::min(s4 + m4, s5 + m5)) + reach;
        const float lowIn = std::min(std::min(std::min(s0 - m0, s1 - m1), std::min(s2 - m2, s3 - m3)),
                                     std::min(s4 - m4, s5 - m5)) - reach;
        // Outside = 0, Intersects = 1, Inside = 2 (see Containment).
        out[i] = static_cast<std::uint8_t>(static_cast<int>(lowOut >= 0.0f) + static_cast<int>(lowIn > 0.0f));
    }
}

}  // namespace

SphereArrayCuller::SphereArrayCuller(const Frustum& frustum, const Vec3& origin) : origin_(origin) {
    for (int i = 0; i < Frustum::kPlaneCount; ++i) {
        if (!(frustum.activePlanes() & (1u << i))) {
            // An inactive plane: every sphere is far inside it.
            nx_[i] = ny_[i] = nz_[i] = 0.0f;
            d_[i] = std::numeric_limits<float>::max();
            dMargin_[i] = 0.0f;
            continue;
        }
        const Vec4& p = frustum.plane(i);
        const double dRel = glm::dot(Vec3(p), origin) + p.w;  // plane offset seen from the origin
        nx_[i] = static_cast<float>(p.x);
        ny_[i] = static_cast<float>(p.y);
        nz_[i] = static_cast<float>(p.z);
        d_[i] = static_cast<float>(dRel);
        dMargin_[i] = kRelMargin * static_cast<float>(std::abs(dRel));
    }
}

void SphereArrayCuller::classify(const SphereArrays& s, std::span<Containment> out, OpTally* ops) const {
    const std::size_t n = s.x.size();
    if (s.y.size() != n || s.z.size() != n || s.radius.size() != n)
        throw std::invalid_argument("SphereArrayCuller::classify: argument 'spheres' has arrays of different lengths");
    if (out.size() < n)
        throw std::invalid_argument("SphereArrayCuller::classify: argument 'out' is shorter than the sphere arrays");
    static_assert(sizeof(Containment) == 1);
    classifyKernel(s.x.data(), s.y.data(), s.z.data(), s.radius.data(), n, nx_.data(), ny_.data(),
                   nz_.data(), d_.data(), dMargin_.data(), reinterpret_cast<std::uint8_t*>(out.data()));
    THRONG_TALLY(ops, kOpsPerSphere.mults * n, kOpsPerSphere.adds * n, 0, 0);
}

}  // namespace throng
