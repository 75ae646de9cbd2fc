// SphereArrayCuller: the flat float culler agrees with the double Frustum and is never less
// conservative, near and far from the world origin.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#if defined(__x86_64__)
#include <cpuid.h>
#endif

#include "throng/scenegraph/SphereArrayCuller.h"
#include "throng/testkit/RandomScenes.h"

using namespace throng;

namespace {

struct Agreement {
    int total = 0, same = 0;
};

Agreement compareWithDouble(std::mt19937_64& rng, const Vec3& origin, int cameras, int spheresPerCamera) {
    std::uniform_real_distribution<double> u(-1, 1);
    Agreement a;
    for (int c = 0; c < cameras; ++c) {
        const Camera cam = testkit::randomCamera(rng, 100.0, origin);
        const Frustum f = cam.frustum();
        const SphereArrayCuller culler(f, cam.eye());
        std::vector<float> x, y, z, r;
        std::vector<BoundingSphere> spheres;
        for (int i = 0; i < spheresPerCamera; ++i) {
            const Vec3 centre = cam.eye() + Vec3(u(rng), u(rng), u(rng)) * 200.0;
            const double radius = std::abs(u(rng)) * 10.0;
            // The float arrays hold what the double sphere holds, rounded: classify the rounded sphere.
            const Vec3 rel = centre - cam.eye();
            x.push_back(static_cast<float>(rel.x));
            y.push_back(static_cast<float>(rel.y));
            z.push_back(static_cast<float>(rel.z));
            r.push_back(static_cast<float>(radius));
            spheres.emplace_back(cam.eye() + Vec3(x.back(), y.back(), z.back()), static_cast<double>(r.back()));
        }
        std::vector<Containment> out(spheres.size());
        culler.classify({x, y, z, r}, out);
        for (std::size_t i = 0; i < spheres.size(); ++i) {
            const Containment exact = f.classify(spheres[i]);
            if (out[i] == Containment::Outside) {
                EXPECT_EQ(exact, Containment::Outside) << "float rejected a visible sphere";
            }
            if (out[i] == Containment::Inside) {
                EXPECT_EQ(exact, Containment::Inside) << "float claimed inside";
            }
            ++a.total;
            a.same += out[i] == exact;
        }
    }
    return a;
}

#if defined(__x86_64__)
// Whether XGETBV with ECX = 1 (XINUSE: which register states are not in their initial state) exists.
bool canReadStatesInUse() {
    unsigned a = 0, b = 0, c = 0, d = 0;
    return __get_cpuid_count(0xd, 1, &a, &b, &c, &d) && (a & (1u << 2));
}

// XINUSE bits 2 and 6: the upper halves of ymm0-15 and zmm0-15 hold something.
std::uint64_t dirtyUpperHalves() {
    std::uint32_t lo = 0, hi = 0;
    asm volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(1));
    return ((std::uint64_t(hi) << 32) | lo) & ((1u << 2) | (1u << 6));
}

__attribute__((target("avx"))) void clearUpperHalves() { asm volatile("vzeroupper"); }
#endif

}  // namespace

// The kernel is compiled for wider instruction sets than the rest of Throng: it must leave no dirty
// upper register halves behind, or every SSE instruction after it pays for them on Intel CPUs
// (GCC 12's AVX-512 clone did, and made actor processing three times slower).
TEST(SphereArrayCuller, LeavesNoDirtyUpperRegisterHalves) {
#if defined(__x86_64__)
    if (!canReadStatesInUse()) GTEST_SKIP() << "this CPU cannot say which register states are in use (XGETBV 1)";
    std::mt19937_64 rng(7);
    const Camera cam = testkit::randomCamera(rng, 100.0, Vec3(0.0));
    const SphereArrayCuller culler(cam.frustum(), cam.eye());
    for (std::size_t n = 1; n <= 300; ++n) {  // every remainder of every vector width
        std::vector<float> x(n, 1.0f), y(n, 2.0f), z(n, -30.0f), r(n, 0.5f);
        std::vector<Containment> out(n);
        clearUpperHalves();
        culler.classify({x, y, z, r}, out);
        ASSERT_EQ(dirtyUpperHalves(), 0u) << n << " spheres";
    }
#else
    GTEST_SKIP() << "x86-64 only";
#endif
}

TEST(SphereArrayCuller, AgreesWithDoubleNearTheOrigin) {
    std::mt19937_64 rng(5);
    const Agreement a = compareWithDouble(rng, Vec3(0.0), 200, 500);
    EXPECT_GT(double(a.same) / a.total, 0.999) << a.same << " of " << a.total;
}

TEST(SphereArrayCuller, AgreesWithDoubleTenThousandKilometresAway) {
    std::mt19937_64 rng(6);
    const Agreement a = compareWithDouble(rng, Vec3(1e7, -3e6, 1e7), 200, 500);
    EXPECT_GT(double(a.same) / a.total, 0.999) << a.same << " of " << a.total;
}

TEST(SphereArrayCuller, RejectsMismatchedArrays) {
    const SphereArrayCuller culler(Frustum(), Vec3(0.0));
    std::vector<float> a(4), b(3);
    std::vector<Containment> out(4);
    EXPECT_THROW(culler.classify({a, a, b, a}, out), std::invalid_argument);
    std::vector<Containment> shortOut(2);
    EXPECT_THROW(culler.classify({a, a, a, a}, shortOut), std::invalid_argument);
}

TEST(SphereArrayCuller, FrustumWithoutPlanesHoldsEverything) {
    const SphereArrayCuller culler(Frustum(), Vec3(0.0));
    std::vector<float> v = {1e6f, -3.0f, 0.0f}, r = {1.0f, 0.0f, 5.0f};
    std::vector<Containment> out(3);
    culler.classify({v, v, v, r}, out);
    for (Containment c : out) EXPECT_EQ(c, Containment::Inside);
}
