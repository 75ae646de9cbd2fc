// The pool of morphed impostor cells: the budget caps new cells, the most wanted come first,
// resident cells are reused across frames instead of being made again, a full pool of equally
// wanted cells does not churn, and bad cells are refused. Also the grid-sampled morph: step 1 is
// the per-pixel morph itself, and a 4-pixel grid stays close to it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "throng/render/GridMorph.h"
#include "throng/render/MorphPool.h"

namespace throng {
namespace {

TEST(MorphPool, BudgetCapsNewCellsAndTheMostWantedComeFirst) {
    MorphPool pool(8, 4, 10);
    pool.beginFrame();
    for (std::uint32_t v = 0; v < 6; ++v)
        for (std::uint32_t n = 0; n <= v; ++n) pool.want(1, v);  // view v wanted v + 1 times
    const auto fills = pool.resolve(3);
    ASSERT_EQ(fills.size(), 3u);
    EXPECT_EQ(fills[0].view, 5u);
    EXPECT_EQ(fills[1].view, 4u);
    EXPECT_EQ(fills[2].view, 3u);
    EXPECT_EQ(pool.statistics().wanted, 6u);
    EXPECT_EQ(pool.statistics().made, 3u);
    EXPECT_EQ(pool.statistics().deferred, 3u);
    EXPECT_GE(pool.slotOf(1, 5), 0);
    EXPECT_EQ(pool.slotOf(1, 0), -1);  // deferred: the renderer shows a stored key-frame
    for (const MorphFill& f : fills) EXPECT_EQ(f.keyframe, 1);
}

TEST(MorphPool, ResidentCellsAreReusedAcrossFrames) {
    MorphPool pool(8, 4, 10);
    for (int frame = 0; frame < 3; ++frame) {
        pool.beginFrame();
        for (std::uint32_t v = 0; v < 5; ++v) pool.want(3, v);
        const auto fills = pool.resolve(-1);
        EXPECT_EQ(fills.size(), frame == 0 ? 5u : 0u) << "frame " << frame;
        EXPECT_EQ(pool.statistics().resident, frame == 0 ? 0u : 5u);
    }
}

TEST(MorphPool, FullPoolOfEquallyWantedCellsDoesNotChurn) {
    // Twice as many cells wanted as there are slots, equally, frame after frame: after the first
    // frame fills the pool, no resident cell gives way to an equal one.
    MorphPool pool(4, 2, 8);
    std::uint64_t made = 0;
    for (int frame = 0; frame < 10; ++frame) {
        pool.beginFrame();
        for (std::uint32_t v = 0; v < 8; ++v) pool.want(1, v);
        made += pool.resolve(2).size();
    }
    EXPECT_EQ(made, 4u);
}

TEST(MorphPool, ClearlyMoreWantedCellsReplaceResidentOnes) {
    MorphPool pool(2, 2, 8);
    for (int frame = 0; frame < 5; ++frame) {
        pool.beginFrame();
        pool.want(1, 0), pool.want(1, 1);
        pool.resolve(-1);
    }
    ASSERT_GE(pool.slotOf(1, 0), 0);
    ASSERT_GE(pool.slotOf(1, 1), 0);
    for (int frame = 0; frame < 20; ++frame) {  // demand moves to views 6 and 7
        pool.beginFrame();
        for (int n = 0; n < 4; ++n) pool.want(1, 6), pool.want(1, 7);
        pool.resolve(1);
    }
    EXPECT_GE(pool.slotOf(1, 6), 0);
    EXPECT_GE(pool.slotOf(1, 7), 0);
    EXPECT_EQ(pool.slotOf(1, 0), -1);
}

TEST(MorphPool, ZeroSlotsOrZeroBudgetMakeNothing) {
    MorphPool empty(0, 2, 4);
    empty.beginFrame();
    empty.want(1, 2);
    EXPECT_TRUE(empty.resolve(-1).empty());
    EXPECT_EQ(empty.statistics().deferred, 1u);
    MorphPool pool(4, 2, 4);
    pool.beginFrame();
    pool.want(1, 2);
    EXPECT_TRUE(pool.resolve(0).empty());
    EXPECT_EQ(pool.slotOf(1, 2), -1);
}

TEST(MorphPool, BadArgumentsAreRefused) {
    EXPECT_THROW(MorphPool(-1, 2, 4), std::invalid_argument);
    EXPECT_THROW(MorphPool(4, 0, 4), std::invalid_argument);
    EXPECT_THROW(MorphPool(4, 2, 0), std::invalid_argument);
    MorphPool pool(4, 2, 4);
    pool.beginFrame();
    EXPECT_THROW(pool.want(2, 0), std::out_of_range);
    EXPECT_THROW(pool.want(-1, 0), std::out_of_range);
    EXPECT_THROW(pool.want(0, 4), std::out_of_range);
    EXPECT_THROW((void)pool.slotOf(5, 0), std::out_of_range);
}

// A premultiplied test card: a disc of varying colour on transparent black.
Image card(int size, float cx, float cy) {
    Image image;
    image.width = image.height = size;
    image.rgba.assign(static_cast<std::size_t>(size) * size * 4, 0);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float dx = static_cast<float>(x) + 0.5f - cx, dy = static_cast<float>(y) + 0.5f - cy;
            if (dx * dx + dy * dy > 0.09f * static_cast<float>(size * size)) continue;
            std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * size + x) * 4];
            p[0] = static_cast<std::uint8_t>(4 * x), p[1] = static_cast<std::uint8_t>(4 * y), p[2] = 128, p[3] = 255;
        }
    return image;
}

TEST(GridMorph, StepOneIsThePerPixelMorphAndAFourPixelGridStaysClose) {
    const Image a = card(64, 24, 30), b = card(64, 40, 34);
    const std::vector<FeatureLine> la{{{20, 20}, {28, 40}}, {{10, 50}, {30, 52}}}, lb{{{36, 22}, {40, 44}}, {{30, 58}, {46, 48}}};  // each line moves its own way
    std::vector<FeatureLine> target;
    interpolateLines(la, lb, 0.5f, target);
    const Image exact = morphImages(a, la, b, lb, target, 0.5f);
    EXPECT_EQ(morphImagesOnGrid(a, la, b, lb, target, 0.5f, {}, 1).rgba, exact.rgba);
    const Image grid = morphImagesOnGrid(a, la, b, lb, target, 0.5f, {}, 4);
    double sum = 0.0;
    std::size_t over = 0;
    for (std::size_t i = 0; i < exact.rgba.size(); ++i) {
        const int d = std::abs(int(exact.rgba[i]) - int(grid.rgba[i]));
        sum += d;
        over += d > 32;
    }
    EXPECT_LT(sum / double(exact.rgba.size()), 2.0);          // mean difference under 2/255
    EXPECT_LT(double(over) / double(exact.rgba.size()), 0.02);  // and few large ones (at silhouettes)
    EXPECT_NE(grid.rgba, exact.rgba);                           // but it is an approximation
}

TEST(GridMorph, BadInputIsRefused) {
    const Image a = card(16, 8, 8), b = card(32, 8, 8);
    const std::vector<FeatureLine> one{{{1, 1}, {5, 5}}}, none;
    EXPECT_THROW(morphImagesOnGrid(a, one, b, one, one, 0.5f, {}, 4), std::invalid_argument);
    EXPECT_THROW(morphImagesOnGrid(a, one, a, none, one, 0.5f, {}, 4), std::invalid_argument);
    EXPECT_THROW(morphImagesOnGrid(a, one, a, one, one, NAN, {}, 4), std::invalid_argument);
    EXPECT_THROW(morphImagesOnGrid(Image{}, one, a, one, one, 0.5f, {}, 4), std::invalid_argument);
}

}  // namespace
}  // namespace throng
