// The town drawn at the cost of what shows (issue 13): the default scene's town (the tiles of the
// shared assets) with 10 actors, from cameras along its path, headless at 640 x 360.
//
//   * The cheaper drawing (front-to-back order, constant faces shaded per vertex) against the old
//     drawing (list order, every face shaded per pixel), at full detail (no town LOD): the images
//     must agree within the golden-image tolerance (GoldenTolerance: at most 0.5 % of the pixels
//     over 8/255, PSNR >= 35 dB), and the new drawing must really take its cheap path.
//   * Town LOD (full tiles to 50 m, half the triangles to 100 m, a quarter beyond, as bench_frame
//     measures it) draws fewer triangles from the overview camera than the full town; its image
//     difference against full detail is reported (a LOD is meant to change the picture a little:
//     the number is the price, not a pass mark).
//   * The town frame drawn through EGL's surfaceless platform agrees with the same frame drawn
//     through OSMesa within the golden-image tolerance, from every camera above.

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "RenderTestSupport.h"
#include "throng/testkit/Assets.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/render/GlRenderer.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/render/EglContext.h"
#include "throng/render/OsMesaContext.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"

namespace throng {
namespace {

constexpr int kWidth = 640, kHeight = 360;

// The default scene with 10 actors, its town at full detail or with town LOD.
std::unique_ptr<sim::Simulation> defaultTown(bool townLod) {
    sim::SceneDescription scene = sim::parseSceneFile(testkit::townDefaultScene());
    sim::scaleActors(scene, 10);
    scene.town->lod.clear();
    scene.town->lodScale = 0.0;  // the levels at their declared distances
    if (townLod) scene.town->lod = {{50.0, 1.0}, {100.0, 0.5}, {std::numeric_limits<double>::infinity(), 0.25}};
    auto world = sim::Simulation::build(std::move(scene));
    for (int i = 0; i < 30; ++i) world->step();  // walkers leave their spawn points
    return world;
}

struct Frame {
    Image image;
    RenderStatistics stats;
};

Frame render(GlRenderer& renderer, const Camera& camera, const DrawList& list) {
    renderer.beginFrame(camera);
    renderer.draw(list);
    Frame f{renderer.readFrame(), renderer.statistics()};
    renderer.endFrame();
    return f;
}

RendererOptions oldDrawing() {
    RendererOptions o;
    o.frontToBack = false;
    o.constantFaces = false;
    return o;
}

class TownDrawTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() { context_ = std::make_shared<OsMesaContext>(kWidth, kHeight); }
    static void TearDownTestSuite() { context_.reset(); }
    static std::shared_ptr<OsMesaContext> context_;
};
std::shared_ptr<OsMesaContext> TownDrawTest::context_;

TEST_F(TownDrawTest, NewDrawingMatchesOldAtFullDetail) {
    auto world = defaultTown(false);
    ActorProcessor processor(world->crowd());
    GlRenderer before(context_, oldDrawing()), after(context_);
    ASSERT_TRUE(after.options().frontToBack && after.options().constantFaces) << "the defaults are the new drawing";
    const double aspect = double(kWidth) / kHeight;
    for (double t : {0.0, 5.0, 9.0, 13.0, 18.0}) {  // overview, descent, street, rising, far side
        SCOPED_TRACE("camera at path time " + std::to_string(t) + " s");
        const Camera camera = world->camera().at(t, aspect);
        processor.processFrame(world->root(), camera, world->now().time);
        const Frame old = render(before, camera, processor.drawList());
        const Frame now = render(after, camera, processor.drawList());
        EXPECT_EQ(old.stats.triangles, now.stats.triangles) << "the same triangles, drawn another way";
        EXPECT_EQ(old.stats.constantTriangles + old.stats.flatLitTriangles, 0u);
        EXPECT_GT(now.stats.constantTriangles, now.stats.triangles / 5) << "the cheap path must really be taken";
        EXPECT_GT(now.stats.flatLitTriangles, 0u) << "so must the flat-lit one";
        EXPECT_GT(test::coveredPixels(old.image), std::size_t(kWidth * kHeight / 4)) << "the town must be in view";
        const testkit::ImageDifference d = testkit::compareImages(old.image, now.image, test::GoldenTolerance{}.threshold);
        std::printf("t = %4.1f s: %llu of %llu triangles constant, %llu flat-lit; %zu pixels over %d (%.4f %%), max %d, PSNR %.1f dB\n",
                    t, (unsigned long long)now.stats.constantTriangles, (unsigned long long)now.stats.triangles,
                    (unsigned long long)now.stats.flatLitTriangles,
                    d.pixelsOverThreshold, test::GoldenTolerance{}.threshold, 100.0 * d.fractionOverThreshold,
                    d.maxChannelDifference, d.psnr);
        EXPECT_LE(d.fractionOverThreshold, test::GoldenTolerance{}.maxFraction);
        EXPECT_GE(d.psnr, test::GoldenTolerance{}.minPsnr);
        if (d.fractionOverThreshold > test::GoldenTolerance{}.maxFraction || d.psnr < test::GoldenTolerance{}.minPsnr) {
            const std::string name = "town_t" + std::to_string(int(t));
            test::writeOutput(old.image, name + "-old");
            test::writeOutput(now.image, name + "-new");
            test::writeOutput(testkit::differenceImage(old.image, now.image), name + "-diff");
        }
    }
}

TEST_F(TownDrawTest, TownLodDrawsFewerTrianglesInTheOverview) {
    auto full = defaultTown(false);
    auto lod = defaultTown(true);
    ActorProcessor fullProcessor(full->crowd()), lodProcessor(lod->crowd());
    GlRenderer renderer(context_);
    const Camera camera = full->camera().at(0.0, double(kWidth) / kHeight);  // the overview
    fullProcessor.processFrame(full->root(), camera, full->now().time);
    lodProcessor.processFrame(lod->root(), camera, lod->now().time);
    const Frame a = render(renderer, camera, fullProcessor.drawList());
    const Frame b = render(renderer, camera, lodProcessor.drawList());
    EXPECT_LT(double(b.stats.triangles), 0.8 * double(a.stats.triangles));
    const testkit::ImageDifference d = testkit::compareImages(a.image, b.image, test::GoldenTolerance{}.threshold);
    std::printf("overview: %llu triangles at full detail, %llu with town LOD; image difference: %zu pixels over %d "
                "(%.3f %%), mean %.3f, PSNR %.1f dB\n",
                (unsigned long long)a.stats.triangles, (unsigned long long)b.stats.triangles, d.pixelsOverThreshold,
                test::GoldenTolerance{}.threshold, 100.0 * d.fractionOverThreshold, d.meanAbsoluteDifference, d.psnr);
    RecordProperty("town_lod_psnr", std::to_string(d.psnr));
    RecordProperty("town_lod_fraction_over_threshold", std::to_string(d.fractionOverThreshold));
    test::writeOutput(a.image, "town_overview-full");
    test::writeOutput(b.image, "town_overview-lod");
}

TEST_F(TownDrawTest, TownFrameThroughEglMatchesOsMesa) {
    auto world = defaultTown(false);
    ActorProcessor processor(world->crowd());
    auto egl = std::make_shared<EglContext>(kWidth, kHeight, EglContext::Platform::Surfaceless);
    GlRenderer throughOsMesa(context_), throughEgl(egl);
    const double aspect = double(kWidth) / kHeight;
    for (double t : {0.0, 5.0, 9.0, 13.0, 18.0}) {
        SCOPED_TRACE("camera at path time " + std::to_string(t) + " s");
        const Camera camera = world->camera().at(t, aspect);
        processor.processFrame(world->root(), camera, world->now().time);
        const Frame a = render(throughOsMesa, camera, processor.drawList());
        const Frame b = render(throughEgl, camera, processor.drawList());
        EXPECT_EQ(a.stats.triangles, b.stats.triangles);
        EXPECT_GT(test::coveredPixels(b.image), std::size_t(kWidth * kHeight / 4)) << "the town must be in view";
        const testkit::ImageDifference d = testkit::compareImages(a.image, b.image, test::GoldenTolerance{}.threshold);
        std::printf("t = %4.1f s: EGL against OSMesa: %zu pixels over %d (%.4f %%), max %d, PSNR %.1f dB\n", t,
                    d.pixelsOverThreshold, test::GoldenTolerance{}.threshold, 100.0 * d.fractionOverThreshold,
                    d.maxChannelDifference, d.psnr);
        EXPECT_LE(d.fractionOverThreshold, test::GoldenTolerance{}.maxFraction);
        EXPECT_GE(d.psnr, test::GoldenTolerance{}.minPsnr);
        if (d.fractionOverThreshold > test::GoldenTolerance{}.maxFraction || d.psnr < test::GoldenTolerance{}.minPsnr) {
            const std::string name = "town_egl_t" + std::to_string(int(t));
            test::writeOutput(a.image, name + "-osmesa");
            test::writeOutput(b.image, name + "-egl");
            test::writeOutput(testkit::differenceImage(a.image, b.image), name + "-diff");
        }
    }
}

}  // namespace
}  // namespace throng
