// Frustum-sphere classification throughput: spheres in flat float arrays (SphereArrayCuller, the
// Filament-style culler) against one double Frustum::classify call per sphere. Reports spheres per
// second for arrays that fit in L1, L2 and main memory.

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "throng/scenegraph/SphereArrayCuller.h"
#include "throng/testkit/RandomScenes.h"

using namespace throng;

namespace {

struct Spheres {
    Camera camera;
    std::vector<float> x, y, z, r;
    std::vector<BoundingSphere> exact;
};

Spheres makeSpheres(std::size_t n) {
    std::mt19937_64 rng(1);
    Spheres s;
    s.camera.setPerspective(1.0, 16.0 / 9.0, 0.1, 500.0);
    s.camera.setLookAt(Vec3(0, 2, 0), Vec3(0, 0, -100), Vec3(0, 1, 0));
    std::uniform_real_distribution<double> u(-300, 300), rad(0.3, 3.0);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 c(u(rng), 0.5 * u(rng), u(rng));
        const double r = rad(rng);
        const Vec3 rel = c - s.camera.eye();
        s.x.push_back(static_cast<float>(rel.x));
        s.y.push_back(static_cast<float>(rel.y));
        s.z.push_back(static_cast<float>(rel.z));
        s.r.push_back(static_cast<float>(r));
        s.exact.emplace_back(c, r);
    }
    return s;
}

void BM_SphereArrayCuller(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const Spheres s = makeSpheres(n);
    const SphereArrayCuller culler(s.camera.frustum(), s.camera.eye());
    std::vector<Containment> out(n);
    for (auto _ : state) {
        culler.classify({s.x, s.y, s.z, s.r}, out);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
    state.counters["spheres_per_s"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_SphereArrayCuller)->Arg(1 << 10)->Arg(1 << 14)->Arg(1 << 18)->Arg(1 << 22);

void BM_FrustumClassifyDouble(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const Spheres s = makeSpheres(n);
    const Frustum f = s.camera.frustum();
    std::vector<Containment> out(n);
    for (auto _ : state) {
        for (std::size_t i = 0; i < n; ++i) out[i] = f.classify(s.exact[i]);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
    state.counters["spheres_per_s"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_FrustumClassifyDouble)->Arg(1 << 10)->Arg(1 << 14)->Arg(1 << 18);

}  // namespace

BENCHMARK_MAIN();
