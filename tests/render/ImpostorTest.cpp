// Impostors of a procedural figure: baking covers every cell, halving the key-frames halves the
// texture (and the view rings too quarters it), the CPU and GPU morphs agree (|difference| <= 2/255 on >= 99.9% of pixels), morphed
// in-betweens beat showing the previous key-frame, the description round-trips through files, and
// the morph cache makes each cell once per frame.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "ImpostorTestSupport.h"
#include "RenderTestSupport.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/Actor.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/render/ImpostorBatcher.h"
#include "throng/render/ImpostorDrawable.h"
#include "throng/render/ImpostorRenderer.h"
#include "throng/scenegraph/Group.h"
#include "throng/render/GpuMorpher.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/testkit/ImageSimilarity.h"
#include "throng/render/MorphCache.h"
#include "throng/render/ProxyWarp.h"

namespace throng {
namespace {

using test::BakedHumanoid;

std::size_t opaquePixels(const Image& image) {
    std::size_t n = 0;
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) n += image.rgba[i] > 0;
    return n;
}

ImpostorAtlas halved() {
    ImpostorAtlas atlas = *BakedHumanoid::get().full;
    atlas.dropOddKeyframes();
    return atlas;
}

TEST(Impostor, BakeFillsEveryCellAndStaysInside) {
    const ImpostorAtlas& atlas = *BakedHumanoid::get().full;
    for (int k = 0; k < atlas.keyframeCount(); ++k)
        for (std::uint32_t v = 0; v < atlas.views().viewCount(); ++v) {
            const Image cell = atlas.cell(v, k);
            const std::size_t covered = opaquePixels(cell);
            EXPECT_GT(covered, 100u) << "view " << v << " key-frame " << k;
            EXPECT_LT(covered, cell.rgba.size() / 4 / 2) << "the figure should not fill its cell";
            // The border stays empty: the volume holds every pose.
            for (int x = 0; x < cell.width; ++x) EXPECT_EQ(cell.rgba[static_cast<std::size_t>(x) * 4 + 3], 0);
            for (const FeatureLine& l : atlas.lines(v, k)) {
                EXPECT_GE(l.p.x, 0.0f);
                EXPECT_LE(l.p.x, static_cast<float>(atlas.cellSize()));
            }
        }
}

TEST(Impostor, HalfTheKeyframesHalveTheTexture) {
    const ImpostorAtlas atlas = halved();
    EXPECT_EQ(atlas.fullTextureBytes(), BakedHumanoid::get().full->textureBytes());
    EXPECT_LE(static_cast<double>(atlas.textureBytes()), 0.55 * static_cast<double>(atlas.fullTextureBytes()));
    int before = 0, after = 0;
    float t = 0;
    atlas.neighbours(7, before, after, t);  // the last one wraps to the first
    EXPECT_EQ(before, 6);
    EXPECT_EQ(after, 0);
    EXPECT_FLOAT_EQ(t, 0.5f);
}

// The half atlas (seed 000 §5): every other key-frame and every other view ring dropped, the
// pages compacted so the memory really goes; stored cells unchanged, dropped ones refused, and
// each dropped cell's sources the stored cells around it with bilinear shares.
TEST(Impostor, HalfAtlasDropsEveryOtherRingAndKeyframe) {
    const ImpostorAtlas& full = *BakedHumanoid::fourRings().full;
    ImpostorAtlas half = full;
    half.drop(AtlasStorage::Half);
    EXPECT_EQ(half.textureBytes() * 4, full.textureBytes());  // 4 of 8 key-frames, 2 of 4 rings
    EXPECT_LE(static_cast<double>(half.textureBytes()), 0.55 * static_cast<double>(half.fullTextureBytes()));
    const std::uint32_t around = static_cast<std::uint32_t>(full.views().azimuths());
    for (int ring = 0; ring < 4; ++ring) EXPECT_EQ(half.ringStored(ring), ring % 2 == 0) << "ring " << ring;
    for (std::uint32_t v = 0; v < full.views().viewCount(); ++v)
        for (int k = 0; k < full.keyframeCount(); ++k) {
            const bool stored = k % 2 == 0 && (v / around) % 2 == 0;
            ASSERT_EQ(half.cellStored(v, k), stored) << "view " << v << " key-frame " << k;
            if (stored) {
                EXPECT_EQ(half.cell(v, k).rgba, full.cell(v, k).rgba) << "view " << v << " key-frame " << k;
            } else {
                EXPECT_THROW(static_cast<void>(half.cell(v, k)), std::invalid_argument);
            }
            const CellSources from = half.sources(v, k);
            float sum = 0.0f;
            for (int i = 0; i < from.count; ++i) {
                const CellSource& c = from.cells[static_cast<std::size_t>(i)];
                EXPECT_TRUE(half.cellStored(c.view, c.keyframe));
                EXPECT_EQ(c.view % around, v % around) << "a source keeps the azimuth";
                sum += c.weight;
            }
            EXPECT_NEAR(sum, 1.0f, 1e-6f);
            if (stored) {
                EXPECT_EQ(from.count, 1);
            }
        }
    int below = 0, above = 0;
    float t = 0;
    half.ringNeighbours(1, below, above, t);
    EXPECT_EQ(below, 0);
    EXPECT_EQ(above, 2);
    EXPECT_FLOAT_EQ(t, 0.5f);
    half.ringNeighbours(3, below, above, t);  // the top ring: nothing stored above it
    EXPECT_EQ(below, 2);
    EXPECT_EQ(above, 2);
    EXPECT_FLOAT_EQ(t, 0.0f);
    EXPECT_THROW(half.ringNeighbours(2, below, above, t), std::invalid_argument);
    const CellSources both = half.sources(around + 3, 1);  // ring 1, key-frame 1: four cells
    EXPECT_EQ(both.count, 4);
    for (int i = 0; i < both.count; ++i) EXPECT_FLOAT_EQ(both.cells[static_cast<std::size_t>(i)].weight, 0.25f);
    EXPECT_THROW(static_cast<void>(half.sources(full.views().viewCount(), 0)), std::invalid_argument);
    ImpostorAtlas oneRing = *BakedHumanoid::get().full;
    oneRing.dropOddRings();  // two rings: the top one goes
    EXPECT_FALSE(oneRing.ringStored(1));
    const std::size_t bytes = oneRing.textureBytes();
    oneRing.dropOddRings();  // again: nothing more to drop
    EXPECT_EQ(oneRing.textureBytes(), bytes);
    ImpostorAtlas flat("flat", "clip", ViewHemisphere(8, 1), 2, 1.0, 8, {});
    EXPECT_THROW(flat.dropOddRings(), std::invalid_argument) << "a single ring";
}

// A half atlas saved and loaded keeps its rings; an impostor.json whose ring list does not match
// its views is refused, naming the file.
TEST(Impostor, HalfAtlasSavesAndLoads) {
    ImpostorAtlas half = *BakedHumanoid::fourRings().full;
    half.drop(AtlasStorage::Half);
    const auto dir = std::filesystem::temp_directory_path() / "throng-impostor-half-test";
    std::filesystem::remove_all(dir);
    half.save(dir);
    const ImpostorAtlas back = ImpostorAtlas::load(dir);
    EXPECT_EQ(back.textureBytes(), half.textureBytes());
    for (int ring = 0; ring < 4; ++ring) EXPECT_EQ(back.ringStored(ring), half.ringStored(ring));
    for (int k = 0; k < half.keyframeCount(); k += 2) EXPECT_EQ(back.page(k).rgba, half.page(k).rgba);
    std::string json;
    {
        std::ifstream in(dir / "impostor.json");
        json.assign(std::istreambuf_iterator<char>(in), {});
    }
    const std::size_t at = json.find("\"ringsStored\"");
    ASSERT_NE(at, std::string::npos);
    const std::size_t open = json.find('[', at), close = json.find(']', at);
    {
        std::ofstream out(dir / "impostor.json");
        out << json.substr(0, open) << "[true, false]" << json.substr(close + 1);
    }
    try {
        static_cast<void>(ImpostorAtlas::load(dir));
        ADD_FAILURE() << "a ring list of the wrong length loaded";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("ringsStored"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("impostor.json"), std::string::npos) << e.what();
    }
    std::filesystem::remove_all(dir);
}

TEST(Impostor, MorphIntoRefusesBadArguments) {
    GpuMorpher gpu(BakedHumanoid::get().context);
    const std::vector<FeatureLine> one{{{1, 1}, {5, 5}}}, none;
    EXPECT_THROW(gpu.morphInto(0, 0, 1, 0, 2, 64, one, one, one, 0.5f), std::invalid_argument);
    EXPECT_THROW(gpu.morphInto(1, -1, 1, 1, 2, 64, one, one, one, 0.5f), std::invalid_argument);
    EXPECT_THROW(gpu.morphInto(1, 0, 1, 1, 2, 0, one, one, one, 0.5f), std::invalid_argument);
    EXPECT_THROW(gpu.morphInto(1, 0, 1, 1, 2, 64, one, none, one, 0.5f), std::invalid_argument);
    EXPECT_THROW(gpu.morphInto(1, 0, 1, 1, 2, 64, one, one, one, NAN), std::invalid_argument);
}

TEST(Impostor, CpuAndGpuMorphsAgree) {
    const ImpostorAtlas atlas = halved();
    GpuMorpher gpu(BakedHumanoid::get().context);
    MorphCacheOptions options;
    for (int k = 1; k < atlas.keyframeCount(); k += 2)
        for (std::uint32_t v = 0; v < atlas.views().viewCount(); v += 3) {
            const Image cpu = morphDroppedCell(atlas, v, k, options);
            const Image onGpu = morphDroppedCell(atlas, v, k, options, &gpu);
            const testkit::ImageDifference d = testkit::compareImages(cpu, onGpu, 2);
            EXPECT_LE(d.fractionOverThreshold, 0.001) << "view " << v << " key-frame " << k;
            EXPECT_GT(opaquePixels(cpu), 100u);
        }
}

TEST(Impostor, MorphBeatsThePreviousKeyframe) {
    const ImpostorAtlas atlas = halved();
    const ImpostorAtlas& full = *BakedHumanoid::get().full;
    double morphed = 0, previous = 0;
    int n = 0;
    for (int k = 1; k < atlas.keyframeCount(); k += 2)
        for (std::uint32_t v = 0; v < atlas.views().viewCount(); ++v) {
            const Image truth = full.cell(v, k);
            morphed += testkit::normalizedCrossCorrelation(morphDroppedCell(atlas, v, k, {}), truth);
            previous += testkit::normalizedCrossCorrelation(atlas.cell(v, k - 1), truth);
            ++n;
        }
    EXPECT_GT(morphed / n, previous / n);
    EXPECT_GT(morphed / n, 0.7);  // this coarse bake (8 key-frames, 64 px) gives about 0.78
    std::printf("NCC morphed %.4f previous %.4f\n", morphed / n, previous / n);
}

TEST(Impostor, SavesAndLoads) {
    const ImpostorAtlas atlas = halved();
    const auto dir = std::filesystem::temp_directory_path() / "throng-impostor-test";
    std::filesystem::remove_all(dir);
    atlas.save(dir);
    const ImpostorAtlas back = ImpostorAtlas::load(dir);
    EXPECT_EQ(back.keyframeCount(), atlas.keyframeCount());
    EXPECT_EQ(back.boneNames(), atlas.boneNames());
    EXPECT_EQ(back.textureBytes(), atlas.textureBytes());
    for (int k = 0; k < atlas.keyframeCount(); ++k) {
        EXPECT_EQ(back.stored(k), atlas.stored(k));
        if (atlas.stored(k)) {
            EXPECT_EQ(back.page(k).rgba, atlas.page(k).rgba);
        }
        EXPECT_EQ(back.lines(5, k)[2].q, atlas.lines(5, k)[2].q);
    }
    std::filesystem::remove_all(dir);
}

TEST(Impostor, FeatureFileKeepsNamedBones) {
    ImpostorAtlas atlas = halved();
    const auto file = std::filesystem::temp_directory_path() / "throng-impostor-features.json";
    {
        std::FILE* f = std::fopen(file.c_str(), "w");
        ASSERT_NE(f, nullptr);
        std::fprintf(f, "{\"bones\": [\"%s\", \"%s\"]}", atlas.boneNames()[0].c_str(), atlas.boneNames()[3].c_str());
        std::fclose(f);
    }
    const FeatureLine third = atlas.lines(2, 4)[3];
    atlas.applyFeatureFile(file);
    ASSERT_EQ(atlas.boneCount(), 2u);
    EXPECT_EQ(atlas.lines(2, 4)[1].p, third.p);
    std::filesystem::remove(file);
}

TEST(Impostor, CacheMorphsEachCellOncePerFrame) {
    const ImpostorAtlas atlas = halved();
    MorphCache cache;
    for (int frame = 0; frame < 2; ++frame) {
        cache.beginFrame();
        for (int actor = 0; actor < 50; ++actor) cache.request(atlas, static_cast<std::uint32_t>(actor % 4), 1 + 2 * ((actor / 4) % 2));
        EXPECT_EQ(cache.statistics().requests, 50u);
        EXPECT_EQ(cache.statistics().synthesized, 8u);
        EXPECT_EQ(cache.statistics().hits, 42u);
    }
    EXPECT_THROW(cache.request(atlas, 0, 2), std::invalid_argument);
}

TEST(Impostor, CacheRetainsUpToItsCapacity) {
    const ImpostorAtlas atlas = halved();
    MorphCacheOptions options;
    options.capacity = 3;
    MorphCache cache(options);
    cache.beginFrame();
    for (std::uint32_t v = 0; v < 5; ++v) cache.request(atlas, v, 1);
    EXPECT_EQ(cache.statistics().synthesized, 5u);
    cache.beginFrame();  // keeps the 3 most recently used: views 2, 3, 4
    EXPECT_EQ(cache.statistics().resident, 3u);
    for (std::uint32_t v = 0; v < 5; ++v) cache.request(atlas, v, 1);
    EXPECT_EQ(cache.statistics().hits, 3u);
    EXPECT_EQ(cache.statistics().synthesized, 2u);
}

}  // namespace
}  // namespace throng

namespace throng {
namespace {

// A hybrid scene: one actor near (geometry), four far (impostors) drawn by GlRenderer then
// ImpostorRenderer; and one far actor drawn both ways covers about the same pixels.
// Every wanted cell morphed on the CPU, per pixel, in the frame that needs it.
CrowdRendererOptions cpuMorphing() {
    CrowdRendererOptions ro;
    ro.impostors.source = MorphSource::Cpu;
    ro.impostors.gridStep = 1;
    ro.impostors.backgroundMorph = false;
    ro.impostors.morphBudget = -1;
    return ro;
}

struct HybridScene {
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    Camera camera;

    explicit HybridScene(const std::vector<Vec3>& positions) {
        auto behaviour = std::make_shared<KeyframeBehaviour>();
        for (const Vec3& p : positions) {
            KeyframeBehaviour::Actor a;
            a.tmpl = BakedHumanoid::get().tmpl;
            a.clip = a.tmpl->findClip("walk");
            a.position = p;
            root->addChild(crowd.makeActorNode(crowd.add(a.tmpl, behaviour, behaviour->addActor(a))));
        }
        camera.setPerspective(0.5, 4.0 / 3.0, 0.5, 500.0);
        camera.setLookAt(Vec3(0, 1, 10), Vec3(0, 1, -60));
    }

    // The scene drawn once at clip time `t` (default: a dropped key-frame, so the morph path is
    // drawn); with `frames` > 1 drawn that many times by one renderer, the last returned.
    // `atlas` (default: the humanoid's, odd key-frames dropped, no surface proxy) is what is drawn.
    Image render(double impostorDistance, std::uint64_t* impostors = nullptr, CrowdRendererOptions ro = cpuMorphing(),
                 double t = 0.25, int frames = 1, CrowdRenderStatistics* last = nullptr,
                 std::shared_ptr<ImpostorAtlas> atlas = nullptr) {
        BakedHumanoid& b = BakedHumanoid::get();
        ro.meshes.width = 160, ro.meshes.height = 120;
        ro.meshes.captureFrames = true;
        CrowdRenderer renderer(b.context, ro);
        if (!atlas) {
            atlas = std::make_shared<ImpostorAtlas>(*b.full);
            atlas->dropOddKeyframes();
        }
        auto drawable = std::make_shared<ImpostorDrawable>(atlas);
        ActorProcessor processor(crowd);
        processor.setImpostorDistance(impostorDistance, 1.0);
        processor.setImpostor(*b.tmpl, drawable);
        for (int f = 0; f < frames; ++f) processor.processFrame(*root, camera, t, &renderer);
        if (impostors) *impostors = renderer.statistics().quads.instances;
        if (last) *last = renderer.statistics();
        EXPECT_EQ(renderer.statistics().quads.instances, processor.statistics().impostors);
        return renderer.meshes().lastFrame();
    }
};

std::size_t differentFromClear(const Image& image) {
    const RendererOptions defaults;
    std::size_t n = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4)
        n += std::abs(image.rgba[i] - static_cast<int>(std::lround(defaults.clearColor.r * 255))) > 3 ||
             std::abs(image.rgba[i + 2] - static_cast<int>(std::lround(defaults.clearColor.b * 255))) > 3;
    return n;
}

TEST(Impostor, HybridSceneDrawsFarActorsAsQuads) {
    HybridScene scene({Vec3(1.5, 0, 0), Vec3(-4, 0, -40), Vec3(0, 0, -45), Vec3(4, 0, -50), Vec3(8, 0, -55)});
    std::uint64_t impostors = 0;
    const Image hybrid = scene.render(20.0, &impostors);
    EXPECT_EQ(impostors, 4u);
    const Image geometry = scene.render(0.0);
    const double a = static_cast<double>(differentFromClear(hybrid)), b = static_cast<double>(differentFromClear(geometry));
    EXPECT_GT(a, 0.0);
    // The impostors stand where the figures stand, about as big (cell filtering blurs the edges).
    EXPECT_NEAR(a / b, 1.0, 0.35) << a << " pixels as impostors, " << b << " as geometry";
    test::writeOutput(hybrid, "impostor-hybrid");
    test::writeOutput(geometry, "impostor-geometry");
}

// The view choice (the scene's representation.impostorViews and impostorSmoothstep): far actors seen
// between baked views look different snapped to the nearest view, blended, and blended with the
// smoothstep; the impostors cover the same place whichever.
TEST(Impostor, TheViewChoiceChangesWhatImpostorsShow) {
    HybridScene scene({Vec3(-5, 0, -22), Vec3(-1.5, 0, -24), Vec3(2, 0, -23), Vec3(5.5, 0, -25)});
    CrowdRendererOptions nearest = cpuMorphing(), blend = cpuMorphing(), smooth = cpuMorphing();
    nearest.views.nearest = true;
    smooth.views.smoothstep = true;
    const Image a = scene.render(20.0, nullptr, nearest, 0.0), b = scene.render(20.0, nullptr, blend, 0.0),
                c = scene.render(20.0, nullptr, smooth, 0.0);
    const testkit::ImageDifference snapped = testkit::compareImages(a, b, 2), sharpened = testkit::compareImages(b, c, 2);
    std::printf("view choice: nearest against blend %zu pixels (max %d), smoothstep against blend %zu (max %d)\n",
                snapped.pixelsOverThreshold, snapped.maxChannelDifference, sharpened.pixelsOverThreshold, sharpened.maxChannelDifference);
    EXPECT_GE(snapped.pixelsOverThreshold, 20u) << "snapping and blending show the same";
    EXPECT_GE(sharpened.pixelsOverThreshold, 15u) << "the smoothstep changes nothing";
    const double pa = double(differentFromClear(a)), pb = double(differentFromClear(b));
    EXPECT_NEAR(pa / pb, 1.0, 0.15) << pa << " pixels snapped, " << pb << " blended";
    test::writeOutput(a, "impostor-views-nearest");
    test::writeOutput(b, "impostor-views-blend");
    test::writeOutput(c, "impostor-views-smoothstep");
}

// Where impostors are drawn: each actor alone, as an impostor, from several places in the view;
// every pixel its quad covers must lie inside the screen rectangle of its actor's Sklsroot
// Bsphere (the sphere holds every pose the actor takes), and it must cover some.
TEST(Impostor, EachImpostorIsDrawnInsideItsActorsSklsrootSphere) {
    const Vec3 places[] = {Vec3(0, 0, -30), Vec3(-9, 0, -40), Vec3(7, 0, -25), Vec3(3, 0, -45), Vec3(-4, 0, -18)};
    std::size_t drawn = 0;
    for (const Vec3& where : places) {
        HybridScene scene({where});
        std::uint64_t impostors = 0;
        const Image image = scene.render(1.0, &impostors);
        ASSERT_EQ(impostors, 1u);
        // The screen rectangle of the Sklsroot Bsphere: the corners of its bounding cube, projected.
        const Vec3 centre(scene.crowd.skeletonRoot(0)[3]);
        const double r = scene.crowd.skeletonRootRadius(0);
        double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
        for (int k = 0; k < 8; ++k) {
            const Vec4 clip = scene.camera.viewProjection() * Vec4(centre + r * Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1), 1.0);
            ASSERT_GT(clip.w, 0.0);
            const double x = (clip.x / clip.w * 0.5 + 0.5) * image.width, y = (0.5 - clip.y / clip.w * 0.5) * image.height;
            x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
        }
        const RendererOptions defaults;
        std::size_t inside = 0, outside = 0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const std::size_t i = 4 * (std::size_t(y) * std::size_t(image.width) + std::size_t(x));
                const bool covered = std::abs(image.rgba[i] - int(std::lround(defaults.clearColor.r * 255))) > 3 ||
                                     std::abs(image.rgba[i + 2] - int(std::lround(defaults.clearColor.b * 255))) > 3;
                if (!covered) continue;
                // A pixel is inside when its centre is (one pixel of slack for filtering at the edge).
                const bool in = x + 0.5 >= x0 - 1 && x + 0.5 <= x1 + 1 && y + 0.5 >= y0 - 1 && y + 0.5 <= y1 + 1;
                (in ? inside : outside) += 1;
            }
        EXPECT_EQ(outside, 0u) << "actor at (" << where.x << ", " << where.z << "): " << outside << " pixels outside its sphere";
        EXPECT_GT(inside, 10u) << "actor at (" << where.x << ", " << where.z << ") is drawn";
        drawn += inside;
    }
    EXPECT_GT(drawn, 100u);
}

// The pool's morphed cells, made by the GL straight into a texture layer, by the CPU, or (as
// before) through the batcher's MorphCache and read back, show the same impostors.
TEST(Impostor, PoolMorphsAgreeWithTheFrameCache) {
    HybridScene scene({Vec3(-4, 0, -30), Vec3(0, 0, -35), Vec3(4, 0, -40), Vec3(8, 0, -45)});
    CrowdRendererOptions gl = cpuMorphing(), cpu = cpuMorphing(), before;
    gl.impostors.source = MorphSource::Gpu;
    before.morphing = ImpostorMorphing::FrameCache;
    CrowdRenderStatistics stats;
    const Image a = scene.render(1.0, nullptr, gl, 0.25, 1, &stats);
    EXPECT_GT(stats.cellsMorphed, 0u);
    EXPECT_EQ(stats.quads.poolOverflows, 0u);
    const Image b = scene.render(1.0, nullptr, cpu);
    const Image c = scene.render(1.0, nullptr, before);
    EXPECT_LT(testkit::compareImages(a, c, 2).fractionOverThreshold, 0.001) << "GL pool against the frame cache";
    EXPECT_LT(testkit::compareImages(b, c, 2).fractionOverThreshold, 0.001) << "CPU pool against the frame cache";
}

// A cell morphed once stays in the pool: the next frames of the same state make none.
TEST(Impostor, PoolKeepsCellsAcrossFrames) {
    HybridScene scene({Vec3(-4, 0, -30), Vec3(0, 0, -35), Vec3(4, 0, -40)});
    CrowdRenderStatistics stats;
    scene.render(1.0, nullptr, cpuMorphing(), 0.25, 3, &stats);
    EXPECT_EQ(stats.cellsMorphed, 0u);
    EXPECT_GT(stats.quads.cellsResident, 0u);
    EXPECT_EQ(stats.quads.cellsResident, stats.quads.cellsWanted);
}

// Quads cut to the part of the cell the views cover draw exactly the pixels whole-cell quads do.
TEST(Impostor, TightQuadsDrawTheSamePixels) {
    HybridScene scene({Vec3(-4, 0, -30), Vec3(0, 0, -35), Vec3(4, 0, -40), Vec3(8, 0, -28)});
    CrowdRendererOptions whole = cpuMorphing(), tight = cpuMorphing();
    whole.impostors.tightQuads = false;
    for (double t : {0.0, 0.25, 0.6}) {  // stored, dropped (morphed), dropped
        const Image a = scene.render(1.0, nullptr, tight, t), b = scene.render(1.0, nullptr, whole, t);
        EXPECT_GT(differentFromClear(a), 50u);
        EXPECT_EQ(a.rgba, b.rgba) << "clip time " << t;
    }
}

// Morphing on another thread: the first frame shows the nearest stored key-frame, the next the
// morphed cells, the same as morphing them on the drawing thread on the same grid.
TEST(Impostor, BackgroundMorphShowsCellsFromTheNextFrame) {
    HybridScene scene({Vec3(-4, 0, -30), Vec3(0, 0, -35), Vec3(4, 0, -40)});
    CrowdRendererOptions background = cpuMorphing(), inline_ = cpuMorphing(), none = cpuMorphing();
    background.impostors.backgroundMorph = true;
    background.impostors.gridStep = inline_.impostors.gridStep = 4;
    none.impostors.morphBudget = 0;
    CrowdRenderStatistics stats;
    const Image first = scene.render(1.0, nullptr, background, 0.25, 1, &stats);
    EXPECT_GT(stats.cellsMorphed, 0u);
    EXPECT_EQ(first.rgba, scene.render(1.0, nullptr, none, 0.25).rgba);  // nothing ready yet
    const Image second = scene.render(1.0, nullptr, background, 0.25, 2, &stats);
    EXPECT_EQ(stats.quads.poolOverflows, 0u);
    EXPECT_GT(stats.quads.backgroundMorphMs, 0.0);
    EXPECT_EQ(second.rgba, scene.render(1.0, nullptr, inline_, 0.25).rgba);
}

// With no budget for morphing, a dropped key-frame shows its nearest stored key-frame: the image
// is the one drawn at that stored key-frame's time, and differs from the morphed one.
TEST(Impostor, ZeroBudgetShowsTheNearestStoredKeyframe) {
    HybridScene scene({Vec3(-4, 0, -30), Vec3(0, 0, -35), Vec3(4, 0, -40)});
    CrowdRendererOptions none = cpuMorphing();
    none.impostors.morphBudget = 0;
    CrowdRenderStatistics stats;
    const Image unmorphed = scene.render(1.0, nullptr, none, 0.25, 1, &stats);  // key-frame 1 of 8 over 2 s: dropped
    EXPECT_EQ(stats.cellsMorphed, 0u);
    EXPECT_GT(stats.quads.poolOverflows, 0u);
    EXPECT_EQ(unmorphed.rgba, scene.render(1.0, nullptr, none, 0.0).rgba);  // key-frame 0: stored
    EXPECT_NE(unmorphed.rgba, scene.render(1.0, nullptr, cpuMorphing(), 0.25).rgba);
}

// A dropped key-frame warped through the figure's surface proxy is nearer the truly baked cell
// than one morphed along the bone lines, on the drawing thread and on the other thread alike; an
// atlas without a proxy is morphed along the lines whatever the option says.
// The pool's dropped key-frames warped through the surface proxy by the GL (GpuProxyWarper, into
// the pool's layers) show what the CPU's warp shows, and nearer the truth than the GL's line morph.
TEST(Impostor, GpuSurfaceProxyWarpShowsWhatTheCpuShows) {
    HybridScene scene({Vec3(-2, 0, -12), Vec3(1, 0, -14), Vec3(3, 0, -11)});
    BakedHumanoid& b = BakedHumanoid::get();
    auto all = std::make_shared<ImpostorAtlas>(*b.full);
    auto withProxy = std::make_shared<ImpostorAtlas>(*b.full);
    withProxy->setProxy(std::make_shared<const ProxyMesh>(b.baker->proxyMesh()));
    withProxy->dropOddKeyframes();
    CrowdRendererOptions cpu = cpuMorphing(), gl = cpuMorphing(), glLines = cpuMorphing();
    gl.impostors.source = MorphSource::Gpu;
    glLines.impostors.source = MorphSource::Gpu;
    glLines.impostors.warp = CellWarp::FeatureLines;
    for (double t : {0.25, 0.75}) {
        const Image truth = scene.render(1.0, nullptr, cpu, t, 1, nullptr, all);
        const Image onCpu = scene.render(1.0, nullptr, cpu, t, 1, nullptr, withProxy);
        const Image onGl = scene.render(1.0, nullptr, gl, t, 1, nullptr, withProxy);
        const Image byLines = scene.render(1.0, nullptr, glLines, t, 1, nullptr, withProxy);
        const testkit::ImageDifference d = testkit::compareImages(onCpu, onGl, 2);
        EXPECT_LE(d.fractionOverThreshold, 0.001) << "clip time " << t << ": " << d.pixelsOverThreshold << " pixels differ";
        const double glPsnr = testkit::compareImages(onGl, truth, 8).psnr, linesPsnr = testkit::compareImages(byLines, truth, 8).psnr;
        EXPECT_GT(glPsnr, linesPsnr + 2.0) << "clip time " << t << ": " << linesPsnr << " dB by lines, " << glPsnr << " through the proxy";
    }
}

TEST(Impostor, SurfaceProxyWarpIsNearerTheBakedKeyframe) {
    HybridScene scene({Vec3(-2, 0, -12), Vec3(1, 0, -14), Vec3(3, 0, -11)});
    BakedHumanoid& b = BakedHumanoid::get();
    auto all = std::make_shared<ImpostorAtlas>(*b.full);  // every key-frame stored: nothing morphed
    auto withProxy = std::make_shared<ImpostorAtlas>(*b.full);
    withProxy->setProxy(std::make_shared<const ProxyMesh>(b.baker->proxyMesh()));
    withProxy->dropOddKeyframes();
    CrowdRendererOptions lines = cpuMorphing(), proxy = cpuMorphing(), background = cpuMorphing();
    lines.impostors.warp = CellWarp::FeatureLines;
    background.impostors.backgroundMorph = true;
    for (double t : {0.25, 0.75}) {  // key-frames 1 and 3 of 8 over 2 s: dropped
        const Image truth = scene.render(1.0, nullptr, proxy, t, 1, nullptr, all);
        const Image byLines = scene.render(1.0, nullptr, lines, t, 1, nullptr, withProxy);
        const Image byProxy = scene.render(1.0, nullptr, proxy, t, 1, nullptr, withProxy);
        const double linesPsnr = testkit::compareImages(byLines, truth, 8).psnr, proxyPsnr = testkit::compareImages(byProxy, truth, 8).psnr;
        EXPECT_GT(proxyPsnr, linesPsnr + 2.0) << "clip time " << t << ": " << linesPsnr << " dB by lines, " << proxyPsnr << " by the proxy";
        EXPECT_EQ(byLines.rgba, scene.render(1.0, nullptr, proxy, t).rgba) << "an atlas without a proxy: lines";
        EXPECT_EQ(byProxy.rgba, scene.render(1.0, nullptr, background, t, 2, nullptr, withProxy).rgba) << "on the other thread";
    }
}

// The half atlas drawn (seed 000 §5): seen from above, where the eye lies between view rings,
// the dropped rings' and key-frames' cells regenerated through the surface proxy (up to four
// stored cells each) are nearer the full atlas's picture than the nearest stored cells a zero
// budget shows, and the GL's warp shows what the CPU's shows. Feature lines (no proxy) regenerate
// dropped rings too, by morphing between the rings in a stored key-frame.
TEST(Impostor, HalfAtlasRegeneratesDroppedRingsWhenDrawn) {
    HybridScene scene({Vec3(-4, 0, -14), Vec3(0, 0, -17), Vec3(4, 0, -15), Vec3(-1, 0, -21)});
    scene.camera.setLookAt(Vec3(0, 11, 2), Vec3(0, 0, -16));  // about 31 degrees down: rings 1 and 2
    const BakedHumanoid& b = BakedHumanoid::fourRings();
    auto full = std::make_shared<ImpostorAtlas>(*b.full);
    auto half = std::make_shared<ImpostorAtlas>(*b.full);
    half->setProxy(std::make_shared<const ProxyMesh>(b.baker->proxyMesh()));
    half->drop(AtlasStorage::Half);
    auto lines = std::make_shared<ImpostorAtlas>(*b.full);
    lines->drop(AtlasStorage::Half);
    CrowdRendererOptions cpu = cpuMorphing(), gl = cpuMorphing(), none = cpuMorphing();
    gl.impostors.source = MorphSource::Gpu;
    none.impostors.morphBudget = 0;
    for (double t : {0.0, 0.25}) {  // key-frame 0 (stored: only rings regenerated) and 1 (dropped)
        CrowdRenderStatistics stats;
        const Image truth = scene.render(1.0, nullptr, cpu, t, 1, nullptr, full);
        const Image onCpu = scene.render(1.0, nullptr, cpu, t, 1, &stats, half);
        EXPECT_GT(stats.cellsMorphed, 0u) << "clip time " << t;
        const Image onGl = scene.render(1.0, nullptr, gl, t, 1, nullptr, half);
        const Image nearest = scene.render(1.0, nullptr, none, t, 1, nullptr, half);
        const Image byLines = scene.render(1.0, nullptr, cpu, t, 1, nullptr, lines);
        const testkit::ImageDifference d = testkit::compareImages(onCpu, onGl, 2);
        EXPECT_LE(d.fractionOverThreshold, 0.001) << "clip time " << t << ": " << d.pixelsOverThreshold << " pixels differ";
        const double warped = testkit::compareImages(onCpu, truth, 8).psnr, shown = testkit::compareImages(nearest, truth, 8).psnr;
        const double morphed = testkit::compareImages(byLines, truth, 8).psnr;
        EXPECT_GT(warped, shown + 2.0) << "clip time " << t << ": " << shown << " dB nearest stored, " << warped << " regenerated";
        EXPECT_GT(morphed, shown) << "clip time " << t << ": " << shown << " dB nearest stored, " << morphed << " by lines";
        std::printf("clip time %.2f: PSNR against the full atlas: regenerated %.2f dB, by lines %.2f dB, nearest stored %.2f dB\n", t,
                    warped, morphed, shown);
        if (t == 0.25) test::writeOutput(onCpu, "impostor-half-atlas"), test::writeOutput(truth, "impostor-full-atlas");
    }
}

// makeDroppedCell (what throng-impostor-quality's runtime section measures) makes a dropped cell
// as the renderer's CPU path does, through the proxy or along the lines, near the truly baked
// cell; a stored cell is refused, naming the template.
TEST(Impostor, MakeDroppedCellIsTheRunTimesCell) {
    const BakedHumanoid& b = BakedHumanoid::fourRings();
    ImpostorAtlas half = *b.full;
    half.setProxy(std::make_shared<const ProxyMesh>(b.baker->proxyMesh()));
    half.drop(AtlasStorage::Half);
    ImpostorRendererOptions proxy, lines;
    lines.warp = CellWarp::FeatureLines;
    double warped = 0, morphed = 0;
    int n = 0;
    for (std::uint32_t v = 0; v < half.views().viewCount(); v += 3)
        for (int k = 0; k < half.keyframeCount(); ++k) {
            if (half.cellStored(v, k)) continue;
            warped += testkit::normalizedCrossCorrelation(makeDroppedCell(half, v, k, proxy), b.full->cell(v, k));
            morphed += testkit::normalizedCrossCorrelation(makeDroppedCell(half, v, k, lines), b.full->cell(v, k));
            ++n;
        }
    ASSERT_GT(n, 0);
    EXPECT_GT(warped / n, 0.9) << "through the proxy";
    EXPECT_GT(warped / n, morphed / n) << "the proxy beats the lines";
    std::printf("dropped cells of the half atlas, NCC: proxy %.4f, lines %.4f over %d cells\n", warped / n, morphed / n, n);
    try {
        static_cast<void>(makeDroppedCell(half, 0, 0, proxy));
        ADD_FAILURE() << "a stored cell was made";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(half.templateName()), std::string::npos) << e.what();
    }
}

// Warped impostors (ImpostorViewChoice::warped, seed 003 §4.1's warp in the vertex stage): each
// impostor drawn as the figure's surface proxy at its own clip time, seen from the real eye and
// textured from the cells the quad would blend, is nearer the skinned figures than the quads, at a
// stored key-frame and between key-frames, seen from above where the eye lies between rings; an
// atlas without a proxy is still drawn as quads.
TEST(Impostor, WarpedImpostorsAreNearerTheFiguresThanQuads) {
    HybridScene scene({Vec3(-3, 0, -12), Vec3(0.5, 0, -14), Vec3(3.5, 0, -11), Vec3(-1, 0, -17)});
    scene.camera.setLookAt(Vec3(0, 6, 2), Vec3(0, 0.8, -14));
    const BakedHumanoid& b = BakedHumanoid::get();
    auto withProxy = std::make_shared<ImpostorAtlas>(*b.full);  // every cell stored: the warp alone is measured
    withProxy->setProxy(std::make_shared<const ProxyMesh>(b.baker->proxyMesh()));
    CrowdRendererOptions quads = cpuMorphing(), warped = cpuMorphing();
    warped.views.warped = true;
    for (double t : {0.0, 0.3, 0.8}) {  // key-frame 0 exactly, then between key-frames 1-2 and 3-4
        const Image truth = scene.render(0.0, nullptr, quads, t);
        CrowdRenderStatistics stats;
        const Image byWarp = scene.render(1.0, nullptr, warped, t, 1, &stats, withProxy);
        EXPECT_EQ(stats.quads.instances, 4u);
        const Image byQuads = scene.render(1.0, nullptr, quads, t, 1, nullptr, withProxy);
        const double w = testkit::compareImages(byWarp, truth, 8).psnr, q = testkit::compareImages(byQuads, truth, 8).psnr;
        EXPECT_GT(w, q) << "clip time " << t << ": quads " << q << " dB, warped " << w << " dB";
        std::printf("clip time %.2f: PSNR against the skinned figures: warped %.2f dB, quads %.2f dB\n", t, w, q);
        if (t == 0.3) test::writeOutput(byWarp, "impostor-warped"), test::writeOutput(byQuads, "impostor-quads"), test::writeOutput(truth, "impostor-skinned");
    }
    auto noProxy = std::make_shared<ImpostorAtlas>(*b.full);
    EXPECT_EQ(scene.render(1.0, nullptr, warped, 0.3, 1, nullptr, noProxy).rgba, scene.render(1.0, nullptr, quads, 0.3, 1, nullptr, noProxy).rgba);
}

// A warped impostor against the CPU reference (warpProxy, the same rule): one actor seen from far
// away through a field of view that fits its cell's square to a cell-sized frame (all but
// orthographic), at a clip time between key-frames and an eye between views; the CPU warps the same
// three cells through the same proxy to the same eye direction and clip time. Bound: at least 99 %
// of the pixels agree on coverage (alpha test at 1/2) and, where both are covered, the colours differ
// by at most 5/255 on average (the GL filters cells with its own bilinear rule and rasterises the
// proxy with its own edge rule; measured 99.85 % and 2.5/255). What it checks is the geometry: the
// pose, the placement and the projection into each cell; at 64 px a fifth of a key-frame's pose
// moves too few pixels to tell (3.3/255 with the pose of the key-frame instead of the clip time).
TEST(Impostor, WarpedImpostorMatchesTheCpuWarp) {
    BakedHumanoid& b = BakedHumanoid::get();
    auto atlas = std::make_shared<ImpostorAtlas>(*b.full);
    atlas->setProxy(std::make_shared<const ProxyMesh>(b.baker->proxyMesh()));
    HybridScene scene({Vec3(0, 0, 0)});
    auto drawable = std::make_shared<ImpostorDrawable>(atlas);
    ActorProcessor processor(scene.crowd);
    processor.setImpostorDistance(1.0, 0.1);
    processor.setImpostor(*b.tmpl, drawable);
    const double t = 0.3;  // 1.2 key-frames into the 2 s clip
    scene.camera.setLookAt(Vec3(0, 60, 200), Vec3(0, 1, 0));
    processor.processFrame(*scene.root, scene.camera, t);
    ImpostorBatcher batcher(ImpostorViewChoice{.warped = true});
    batcher.build(processor.drawList(), scene.camera);
    ASSERT_EQ(batcher.instances().size(), 1u);
    const Vec3 centre = batcher.instances()[0].centre;
    const double distance = 300.0, radius = batcher.instances()[0].halfSize;
    const Vec3 eye = centre + distance * glm::normalize(Vec3(0.45, 0.5, 0.74));
    const int size = atlas->cellSize();
    scene.camera.setPerspective(2.0 * std::atan(radius / distance), 1.0, distance - 20.0, distance + 20.0);
    scene.camera.setLookAt(eye, centre);
    CrowdRendererOptions ro = cpuMorphing();
    ro.views.warped = true;
    ro.meshes.width = ro.meshes.height = size;
    ro.meshes.captureFrames = true;
    CrowdRenderer renderer(b.context, ro);
    processor.processFrame(*scene.root, scene.camera, t, &renderer);
    const Image gpu = renderer.meshes().lastFrame();
    batcher.build(processor.drawList(), scene.camera);
    const ImpostorInstance& inst = batcher.instances()[0];
    const glm::vec3 toEye = glm::normalize(glm::transpose(inst.axes) * glm::vec3(eye - inst.centre));  // in the actor's frame
    std::array<Image, 3> cells;
    std::vector<ProxySource> sources;
    for (std::size_t i = 0; i < 3; ++i)
        if (inst.weights[i] > 0.0f) {
            cells[i] = atlas->cell(inst.views[i], inst.keyframe);
            sources.push_back({&cells[i], atlas->views().direction(inst.views[i]), inst.keyframe, inst.weights[i]});
        }
    ASSERT_GE(sources.size(), 2u) << "the eye should lie between views";
    const Image cpu = warpProxy(*atlas->proxy(), sources, toEye, inst.phase, ProxyWarpOptions{});
    const RendererOptions defaults;
    const int clear[3] = {static_cast<int>(std::lround(defaults.clearColor.r * 255)), static_cast<int>(std::lround(defaults.clearColor.g * 255)),
                          static_cast<int>(std::lround(defaults.clearColor.b * 255))};
    std::size_t agree = 0, both = 0;
    double colour = 0;
    for (std::size_t p = 0; p < static_cast<std::size_t>(size) * static_cast<std::size_t>(size); ++p) {
        const std::uint8_t* g = &gpu.rgba[p * 4];
        const std::uint8_t* c = &cpu.rgba[p * 4];
        const bool gpuCovered = std::abs(g[0] - clear[0]) + std::abs(g[1] - clear[1]) + std::abs(g[2] - clear[2]) > 6;
        const bool cpuCovered = c[3] >= 128;
        agree += gpuCovered == cpuCovered;
        if (gpuCovered && cpuCovered) {
            ++both;
            for (int k = 0; k < 3; ++k) colour += std::abs(static_cast<double>(g[k]) - 255.0 * c[k] / c[3]) / 3.0;
        }
    }
    const double n = static_cast<double>(size) * size;
    ASSERT_GT(both, 100u) << "the figure should cover the frame";
    EXPECT_GE(static_cast<double>(agree) / n, 0.99) << agree << " of " << n << " pixels agree on coverage";
    EXPECT_LE(colour / static_cast<double>(both), 5.0) << "mean colour difference over " << both << " covered pixels";
    std::printf("warped impostor against the CPU warp: %.2f %% of pixels agree on coverage, mean colour difference %.2f/255 over %zu pixels\n",
                100.0 * static_cast<double>(agree) / n, colour / static_cast<double>(both), both);
    test::writeOutput(gpu, "impostor-warped-gpu");
    test::writeOutput(cpu, "impostor-warped-cpu");
}

// Warped impostors of the half atlas (cells regenerated in the pool, their depth layers made with
// them) show nearly what warped impostors of the full atlas show.
TEST(Impostor, WarpedImpostorsReadRegeneratedCells) {
    HybridScene scene({Vec3(-3, 0, -12), Vec3(0.5, 0, -14), Vec3(3.5, 0, -11)});
    scene.camera.setLookAt(Vec3(0, 9, 2), Vec3(0, 0.8, -13));
    const BakedHumanoid& b = BakedHumanoid::fourRings();
    const auto proxy = std::make_shared<const ProxyMesh>(b.baker->proxyMesh());
    auto full = std::make_shared<ImpostorAtlas>(*b.full), half = std::make_shared<ImpostorAtlas>(*b.full);
    full->setProxy(proxy), half->setProxy(proxy);
    half->drop(AtlasStorage::Half);
    CrowdRendererOptions warped = cpuMorphing(), glWarped = cpuMorphing();
    warped.views.warped = true;
    glWarped.views.warped = true;
    glWarped.impostors.source = MorphSource::Gpu;
    for (double t : {0.25, 0.55}) {
        const Image reference = scene.render(1.0, nullptr, warped, t, 1, nullptr, full);
        const Image regenerated = scene.render(1.0, nullptr, warped, t, 1, nullptr, half);
        const Image onGl = scene.render(1.0, nullptr, glWarped, t, 1, nullptr, half);
        const double cpu = testkit::compareImages(regenerated, reference, 8).psnr, gl = testkit::compareImages(onGl, reference, 8).psnr;
        EXPECT_GT(cpu, 35.0) << "clip time " << t;
        EXPECT_GT(gl, 35.0) << "clip time " << t;
        std::printf("clip time %.2f: warped half atlas against warped full atlas: CPU cells %.2f dB, GL cells %.2f dB\n", t, cpu, gl);
    }
}

// A proxy for other cells or key-frames than the atlas's is refused.
TEST(Impostor, AtlasRefusesAProxyOfOtherCells) {
    const BakedHumanoid& b = BakedHumanoid::get();
    ImpostorAtlas atlas(*b.full);
    EXPECT_THROW(atlas.setProxy(std::make_shared<const ProxyMesh>(10, 4, glm::vec3(0.0f), 1.0f, 64)), std::invalid_argument);
    EXPECT_THROW(atlas.setProxy(std::make_shared<const ProxyMesh>(10, 8, glm::vec3(0.0f), 1.0f, 32)), std::invalid_argument);
    EXPECT_NO_THROW(atlas.setProxy(std::make_shared<const ProxyMesh>(10, 8, glm::vec3(0.0f), 1.0f, 64)));
    EXPECT_NO_THROW(atlas.setProxy(nullptr));
    EXPECT_EQ(atlas.proxy(), nullptr);
}

}  // namespace
}  // namespace throng
