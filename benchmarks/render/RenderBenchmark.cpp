// Skinning and frame cost of throng::render, headless (OSMesa, llvmpipe: the "GPU" runs on the CPU).
//
//   BM_CpuSkinningKernel/N      skinMesh() alone on N instances: the CPU path's arithmetic
//   BM_SkinnedFrame/path:P/N    whole frames (palette or vertex upload, draw, glFinish) of N skinned
//                               instances at 160x120, so rasterisation costs little: skinned
//                               vertices per second through each path. P = 0: GPU skinning,
//                               1: CPU skinning, 2: no skinning at all (the same mesh drawn rigid,
//                               instanced: the baseline the skinning cost adds to)
//   BM_Frame1280x720/path:P/N   the same scenes at 1280x720: headless frame time
//
// The mesh is a CesiumMan-sized skinned tube (3264 vertices, 4608 triangles, 19 joints); every
// instance has its own pose. The BM_CesiumMan* cases run the same measurements on the real CesiumMan
// (../shared/assets/characters/CesiumMan.glb, loaded with loadCharacter, textured), each instance at
// its own time of its walk clip:
//   BM_CesiumManCpuSkinningKernel/N, BM_CesiumManFrame/path:P/N (160x120),
//   BM_CesiumManFrame1280x720/path:P/N (headless frame time at 1280x720) Run from a release build (the repetitions give the median and the
// fastest run, interleaved so that other work on the machine spreads over all cases):
//   ./build/release/benchmarks/render/bench_render --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
//   (one command line)
// With THRONG_BENCH_FRAMES=<folder>, each frame benchmark also writes its first frame there as PNG.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <stdexcept>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "throng/testkit/Assets.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/render/CpuSkinning.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/ImageIO.h"
#include "throng/render/OsMesaContext.h"
#include "throng/render/ProceduralMeshes.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng {
namespace {

// A skinned mesh and how to pose instance i of it.
struct Model {
    std::shared_ptr<const MeshData> mesh;
    std::shared_ptr<const MeshDrawable> drawable;
    std::function<void(int, std::vector<glm::mat4>&)> pose;  // palette of instance i
    double spacing = 0.6;  // grid step, metres
    double height = 1.8;   // of the figure, metres
};

// The CesiumMan-sized tube, each instance bent a little differently.
const Model& tubeModel() {
    static const Model model = [] {
        Model m;
        const SkinnedTubeOptions options = cesiumManSizedTube();
        m.mesh = makeSkinnedTube(options);
        m.drawable = std::make_shared<MeshDrawable>(m.mesh);
        m.pose = [options](int i, std::vector<glm::mat4>& palette) {
            bendTubePalette(options, 0.08f * std::sin(0.37f * float(i)), palette, 0.05f * std::cos(0.71f * float(i)));
        };
        return m;
    }();
    return model;
}

// The real CesiumMan (shared assets, loaded with loadCharacter), each instance at its own time of
// its walk clip. Throws if the asset is missing.
const Model& cesiumManModel() {
    static const Model model = [] {
        const std::string path = testkit::sharedAssets() + "/characters/CesiumMan.glb";
        static const CharacterAsset asset = loadCharacter(path);
        const auto tmpl = asset.primaryTemplate();
        if (!tmpl || tmpl->clips().empty() || tmpl->skins().empty()) throw std::runtime_error(path + ": no animated skinned character");
        Model m;
        for (const VaLodLevel& level : tmpl->rootGeometry().levels())
            if (level.skin == 0)
                if (auto d = std::dynamic_pointer_cast<const MeshDrawable>(level.drawable)) m.drawable = d;
        if (!m.drawable) throw std::runtime_error(path + ": no skinned mesh");
        m.mesh = m.drawable->meshPtr();
        m.pose = [tmpl](int i, std::vector<glm::mat4>& palette) {
            std::vector<float> dofs(tmpl->restDofs().begin(), tmpl->restDofs().end());
            std::vector<Affine> transforms(tmpl->nodeCount());
            const AnimationClip& clip = *tmpl->clips()[0];
            clip.sample(*tmpl, 0.137 * i, true, {}, dofs);
            computeModelTransforms(*tmpl, dofs, {}, transforms);
            palette.resize(tmpl->skins()[0].joints.size());
            computeSkinPalette(*tmpl, tmpl->skins()[0], transforms, {}, palette);
        };
        m.spacing = 0.8;
        m.height = 1.5;
        return m;
    }();
    return model;
}

// N posed instances of a model in a square grid, and a camera that sees them all.
struct InstanceGrid {
    const Model& model;
    std::shared_ptr<const MeshData> mesh = model.mesh;
    std::vector<std::vector<glm::mat4>> palettes;
    std::vector<Mat4> matrices;
    DrawList list;
    Camera camera;

    InstanceGrid(const Model& m, int n, double aspect, bool skinned = true) : model(m) {
        const int columns = static_cast<int>(std::ceil(std::sqrt(double(n))));
        const double s = model.spacing;
        palettes.resize(static_cast<std::size_t>(n));
        matrices.reserve(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) {
            model.pose(i, palettes[std::size_t(i)]);
            const double x = (i % columns - 0.5 * (columns - 1)) * s, z = -(i / columns) * s;
            matrices.push_back(glm::translate(Mat4(1.0), Vec3(x, 0.0, z)));
        }
        for (int i = 0; i < n; ++i) {
            DrawItem item;
            item.drawable = model.drawable.get();
            item.world = ItemTransform(matrices[std::size_t(i)]);
            if (skinned) {
                item.skinPalette = palettes[std::size_t(i)].data();
                item.skinPaletteSize = static_cast<std::uint32_t>(palettes[std::size_t(i)].size());
            }
            list.add(item, model.drawable->primitiveCount());
        }
        const double width = s * columns + 1.0;
        camera.setPerspective(std::numbers::pi / 4.0, aspect, 0.1, 1000.0);
        const double back = 0.5 * width / std::tan(std::numbers::pi / 8.0) / std::min(aspect, 1.0) + 1.0;
        camera.setLookAt(Vec3(0.0, model.height + 0.2 * columns, back), Vec3(0.0, 0.5 * model.height, -0.5 * s * columns));
    }
};

std::shared_ptr<OsMesaContext> sharedContext() {
    static auto context = std::make_shared<OsMesaContext>(160, 120);
    return context;
}

void cpuSkinningKernel(benchmark::State& state, const Model& model) {
    const int n = static_cast<int>(state.range(0));
    const InstanceGrid crowd(model, n, 16.0 / 9.0);
    const std::size_t vertices = crowd.mesh->vertexCount();
    std::vector<glm::vec3> positions(vertices * std::size_t(n)), normals(vertices * std::size_t(n));
    for (auto _ : state) {
        for (int i = 0; i < n; ++i)
            skinMesh(*crowd.mesh, crowd.palettes[std::size_t(i)],
                     std::span<glm::vec3>(positions).subspan(vertices * std::size_t(i), vertices),
                     std::span<glm::vec3>(normals).subspan(vertices * std::size_t(i), vertices));
        benchmark::DoNotOptimize(positions.data());
        benchmark::ClobberMemory();
    }
    state.counters["vertices/s"] =
        benchmark::Counter(double(vertices) * n, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_CpuSkinningKernel(benchmark::State& state) { cpuSkinningKernel(state, tubeModel()); }
void BM_CesiumManCpuSkinningKernel(benchmark::State& state) { cpuSkinningKernel(state, cesiumManModel()); }

void runFrames(benchmark::State& state, const Model& model, const char* name, int width, int height) {
    const bool cpu = state.range(0) == 1, rigid = state.range(0) == 2;
    const int n = static_cast<int>(state.range(1));
    auto context = sharedContext();
    RendererOptions options;
    options.width = width;
    options.height = height;
    options.forceCpuSkinning = cpu;
    GlRenderer renderer(context, options);
    const InstanceGrid crowd(model, n, double(width) / height, !rigid);
    renderer.beginFrame(crowd.camera);  // warm-up: uploads the mesh, compiles the shader variant
    renderer.draw(crowd.list);
    if (const char* folder = std::getenv("THRONG_BENCH_FRAMES"))
        writePng(renderer.readFrame(), std::string(folder) + "/" + name + "-" + std::to_string(width) + "x" + std::to_string(height) +
                                           (rigid ? "-rigid-" : cpu ? "-cpu-" : "-gpu-") + std::to_string(n) + ".png");
    renderer.endFrame();
    for (auto _ : state) {
        renderer.beginFrame(crowd.camera);
        renderer.draw(crowd.list);
        renderer.endFrame();  // waits for llvmpipe to finish the frame
    }
    const RenderStatistics& s = renderer.statistics();
    // Skinned vertices; for the rigid baseline, the vertices drawn.
    const double skinned = rigid ? double(s.instances * crowd.mesh->vertexCount())
                                 : double(cpu ? s.cpuSkinnedVertices : s.gpuSkinnedVertices);
    state.counters["vertices/s"] = benchmark::Counter(skinned, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["triangles"] = double(s.triangles);
    state.counters["draw_calls"] = double(s.drawCalls);
    state.counters["draw_cpu_ms"] = s.drawMs;
    state.counters["instances_drawn"] = double(s.instances);
    state.SetLabel(rigid ? "no-skinning" : cpu ? "cpu-skinning" : "gpu-skinning");
}

void BM_SkinnedFrame(benchmark::State& state) { runFrames(state, tubeModel(), "tube", 160, 120); }
void BM_Frame1280x720(benchmark::State& state) { runFrames(state, tubeModel(), "tube", 1280, 720); }
void BM_CesiumManFrame(benchmark::State& state) { runFrames(state, cesiumManModel(), "cesium-man", 160, 120); }
void BM_CesiumManFrame1280x720(benchmark::State& state) { runFrames(state, cesiumManModel(), "cesium-man", 1280, 720); }

// The fastest of the repetitions: on a machine shared with other work it is the best estimate of
// the uncontended cost (the median is reported beside it).
double fastest(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

BENCHMARK(BM_CpuSkinningKernel)->Arg(1)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond)
    ->ComputeStatistics("min", fastest);
BENCHMARK(BM_SkinnedFrame)
    ->ArgNames({"path", "instances"})
    ->ArgsProduct({{0, 1, 2}, {1, 10, 100, 1000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->ComputeStatistics("min", fastest);
BENCHMARK(BM_Frame1280x720)
    ->ArgNames({"path", "instances"})
    ->ArgsProduct({{0, 1, 2}, {1, 10, 100, 1000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->ComputeStatistics("min", fastest);
BENCHMARK(BM_CesiumManCpuSkinningKernel)->Arg(1)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond)
    ->ComputeStatistics("min", fastest);
BENCHMARK(BM_CesiumManFrame)
    ->ArgNames({"path", "instances"})
    ->ArgsProduct({{0, 1, 2}, {1, 10, 100, 1000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->ComputeStatistics("min", fastest);
BENCHMARK(BM_CesiumManFrame1280x720)
    ->ArgNames({"path", "instances"})
    ->ArgsProduct({{0, 1, 2}, {1, 10, 100, 1000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->ComputeStatistics("min", fastest);

}  // namespace
}  // namespace throng

BENCHMARK_MAIN();
