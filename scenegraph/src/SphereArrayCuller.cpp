#include "throng/scenegraph/SphereArrayCuller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace throng {
namespace {

// Relative rounding of the plane offsets (a few ulps of their magnitude).
constexpr float kRelMargin = 8.0f * std::numeric_limits<float>::epsilon();

// The kernel is compiled for several instruction sets and chosen at load time. The planes are
// copied into locals so that they stay in registers; the body (detail::sphereContainment) has no
// branch, so the loop vectorises across spheres.
//
// No AVX-512 clone: GCC 12's returns with dirty upper halves in zmm0-15 (its vzeroupper comes before
// the remainder loop, which moves 512-bit plane constants back into zmm12-15), and on Intel Xeons
// that state slows every SSE instruction run afterwards (the rest of Throng is built for baseline
// x86-64) until something clears it: actor processing of 10k Table-2 actors took 55 ms instead of
// 19, its pose phase 45 ms instead of 9.7. The AVX2 clone ends clean.
__attribute__((target_clones("avx2", "default")))
void classifyKernel(const float* __restrict x, const float* __restrict y, const float* __restrict z,
                    const float* __restrict radius, std::size_t n, const detail::CullPlanes<float>& planes,
                    std::uint8_t* __restrict out) {
    const detail::CullPlanes<float> p = planes;
    for (std::size_t i = 0; i < n; ++i) out[i] = detail::sphereContainment(x[i], y[i], z[i], radius[i], p);
}

}  // namespace

SphereArrayCuller::SphereArrayCuller(const Frustum& frustum, const Vec3& origin) : origin_(origin) {
    for (int i = 0; i < Frustum::kPlaneCount; ++i) {
        if (!(frustum.activePlanes() & (1u << i))) {
            // An inactive plane: every sphere is far inside it.
            planes_.nx[i] = planes_.ny[i] = planes_.nz[i] = 0.0f;
            planes_.d[i] = std::numeric_limits<float>::max();
            planes_.margin[i] = 0.0f;
            continue;
        }
        const Vec4& p = frustum.plane(i);
        const double dRel = glm::dot(Vec3(p), origin) + p.w;  // plane offset seen from the origin
        planes_.nx[i] = static_cast<float>(p.x);
        planes_.ny[i] = static_cast<float>(p.y);
        planes_.nz[i] = static_cast<float>(p.z);
        planes_.d[i] = static_cast<float>(dRel);
        planes_.margin[i] = kRelMargin * static_cast<float>(std::abs(dRel));
    }
}

void SphereArrayCuller::classify(const SphereArrays& s, std::span<Containment> out, OpTally* ops) const {
    const std::size_t n = s.x.size();
    if (s.y.size() != n || s.z.size() != n || s.radius.size() != n)
        throw std::invalid_argument("SphereArrayCuller::classify: argument 'spheres' has arrays of different lengths");
    if (out.size() < n)
        throw std::invalid_argument("SphereArrayCuller::classify: argument 'out' is shorter than the sphere arrays");
    static_assert(sizeof(Containment) == 1);
    classifyKernel(s.x.data(), s.y.data(), s.z.data(), s.radius.data(), n, planes_,
                   reinterpret_cast<std::uint8_t*>(out.data()));
    THRONG_TALLY(ops, kOpsPerSphere.mults * n, kOpsPerSphere.adds * n, 0, 0);
}

}  // namespace throng
