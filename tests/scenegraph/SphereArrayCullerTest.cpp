// SphereArrayCuller: the flat float culler agrees with the double Frustum and is never less
// conservative, near and far from the world origin.

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "throng/scenegraph/SphereArrayCuller.h"
#include "throng/scenes/RandomScenes.h"

using namespace throng;

namespace {

struct Agreement {
    int total = 0, same = 0;
};

Agreement compareWithDouble(std::mt19937_64& rng, const Vec3& origin, int cameras, int spheresPerCamera) {
    std::uniform_real_distribution<double> u(-1, 1);
    Agreement a;
    for (int c = 0; c < cameras; ++c) {
        const Camera cam = scenes::randomCamera(rng, 100.0, origin);
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

}  // namespace

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
