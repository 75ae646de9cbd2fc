// Impostors of a procedural figure: baking covers every cell, halving the key-frames halves the
// texture, the CPU and GPU morphs agree (|difference| <= 2/255 on >= 99.9% of pixels), morphed
// in-betweens beat showing the previous key-frame, the description round-trips through files, and
// the morph cache makes each cell once per frame.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "ImpostorTestSupport.h"
#include "throng/render/GpuMorpher.h"
#include "throng/render/ImageCompare.h"
#include "throng/render/ImageSimilarity.h"
#include "throng/render/MorphCache.h"

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

TEST(Impostor, CpuAndGpuMorphsAgree) {
    const ImpostorAtlas atlas = halved();
    GpuMorpher gpu(BakedHumanoid::get().context);
    MorphCacheOptions options;
    for (int k = 1; k < atlas.keyframeCount(); k += 2)
        for (std::uint32_t v = 0; v < atlas.views().viewCount(); v += 3) {
            const Image cpu = morphDroppedCell(atlas, v, k, options);
            const Image onGpu = morphDroppedCell(atlas, v, k, options, &gpu);
            const ImageDifference d = compareImages(cpu, onGpu, 2);
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
            morphed += normalizedCrossCorrelation(morphDroppedCell(atlas, v, k, {}), truth);
            previous += normalizedCrossCorrelation(atlas.cell(v, k - 1), truth);
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

}  // namespace
}  // namespace throng
