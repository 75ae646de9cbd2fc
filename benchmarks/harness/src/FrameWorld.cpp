#include "throng/bench/FrameWorld.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "throng/testkit/ImageCompare.h"
#include "throng/testkit/ImageSimilarity.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneParser.h"

namespace throng::bench {

std::unique_ptr<sim::Simulation> buildWorld(const std::string& scene, std::int64_t actors) {
    sim::SceneDescription description = sim::parseSceneFile(scene);
    if (actors > 0) sim::scaleActors(description, actors);
    return sim::Simulation::build(std::move(description));
}

std::unique_ptr<ImpostorSet> bakeImpostors(const std::shared_ptr<GlContext>& context, const sim::Simulation& world, AtlasStorage storage,
                                           int cellSize, std::size_t drawProxyVertices) {
    // As throng-town bakes them (apps/support's bakeSceneImpostors), without its progress bar.
    std::vector<ImpostorSet::Source> sources;
    for (const auto& t : world.templates()) sources.push_back({t.tmpl, t.clip});
    ImpostorBakeOptions bake;
    bake.cellSize = cellSize;
    bake.storage = storage;
    bake.drawProxyVertices = drawProxyVertices;
    return std::make_unique<ImpostorSet>(context, sources, bake);
}

std::pair<double, double> impostorDistance(const sim::Simulation& world) {
    const auto& r = world.description().representation;
    const double distance = r.impostorDistance > 0.0 ? r.impostorDistance : 40.0;
    return {distance, r.hysteresis * distance};
}

double cameraTime(const std::string& name) { return name == "street" ? 9.0 : 0.0; }

std::uint64_t stateDigest(const Crowd& crowd) {
    std::uint64_t h = 1469598103934665603ull;
    const auto& ref = crowd.state().refLocal;
    const auto* bytes = reinterpret_cast<const unsigned char*>(ref.data());
    for (std::size_t i = 0; i < ref.size() * sizeof(Mat4); ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    return h;
}

void addFrameError(const Image& frame, const Image& reference, double& psnr, double& ssim, double& off8) {
    const testkit::ImageDifference d = testkit::compareImages(frame, reference, 8);
    psnr += std::min(d.psnr, 99.0);
    ssim += testkit::structuralSimilarity(frame, reference);
    off8 += d.fractionOverThreshold;
}

void fail(const char* program, const std::string& why) {
    std::fprintf(stderr, "%s: %s\n", program, why.c_str());
    std::exit(1);
}

}  // namespace throng::bench
