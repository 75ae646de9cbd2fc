// Image helpers: PNG round trips and errors, and the comparison metrics used by golden tests and
// later by impostor-quality measurements.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "throng/testkit/ImageCompare.h"
#include "throng/render/ImageIO.h"
#include "throng/render/ProceduralMeshes.h"

namespace throng {
namespace {

Image solid(int w, int h, std::uint8_t value) {
    Image image;
    image.name = "solid";
    image.width = w;
    image.height = h;
    image.rgba.assign(static_cast<std::size_t>(w) * h * 4, value);
    return image;
}

TEST(ImageCompareTest, IdenticalImages) {
    const Image a = solid(8, 4, 100);
    const testkit::ImageDifference d = testkit::compareImages(a, a);
    EXPECT_EQ(d.maxChannelDifference, 0);
    EXPECT_EQ(d.pixelsOverThreshold, 0u);
    EXPECT_EQ(d.meanAbsoluteDifference, 0.0);
    EXPECT_TRUE(std::isinf(d.psnr));
}

TEST(ImageCompareTest, KnownDifferences) {
    const Image a = solid(10, 10, 100);
    Image b = a;
    b.rgba[0] = 110;          // pixel 0, red: 10
    b.rgba[4 * 7 + 2] = 97;   // pixel 7, blue: 3
    const testkit::ImageDifference d = testkit::compareImages(a, b, 5);
    EXPECT_EQ(d.maxChannelDifference, 10);
    EXPECT_EQ(d.pixelsOverThreshold, 1u);
    EXPECT_DOUBLE_EQ(d.fractionOverThreshold, 0.01);
    EXPECT_DOUBLE_EQ(d.meanAbsoluteDifference, 13.0 / 400.0);
    EXPECT_NEAR(d.psnr, 10.0 * std::log10(255.0 * 255.0 / (109.0 / 400.0)), 1e-9);
    EXPECT_EQ(testkit::compareImages(a, b, 2).pixelsOverThreshold, 2u);
    const Image diff = testkit::differenceImage(a, b, 8);
    EXPECT_EQ(diff.rgba[0], 80);
    EXPECT_EQ(diff.rgba[4 * 7 + 2], 24);
    EXPECT_EQ(diff.rgba[4], 0);
}

TEST(ImageCompareTest, MismatchesAreErrors) {
    EXPECT_THROW(testkit::compareImages(solid(4, 4, 0), solid(4, 5, 0)), std::invalid_argument);
    EXPECT_THROW(testkit::compareImages(solid(4, 4, 0), Image{}), std::invalid_argument);
    EXPECT_THROW(testkit::compareImages(solid(4, 4, 0), solid(4, 4, 0), 256), std::invalid_argument);
}

TEST(ImageIoTest, PngRoundTrip) {
    const auto checker = makeCheckerImage(32, 4, {255, 0, 0, 255}, {0, 0, 255, 128});
    const auto path = std::filesystem::temp_directory_path() / "throng-image-test.png";
    writePng(*checker, path);
    const Image back = readPng(path);
    std::filesystem::remove(path);
    EXPECT_EQ(back.width, 32);
    EXPECT_EQ(back.height, 32);
    EXPECT_EQ(back.rgba, checker->rgba);
    EXPECT_EQ(back.name, path.string());
}

TEST(ImageIoTest, ErrorsNameTheFile) {
    try {
        readPng("/nonexistent/throng/missing.png");
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/throng/missing.png"), std::string::npos) << e.what();
    }
    EXPECT_THROW(writePng(Image{}, "/tmp/never.png"), std::invalid_argument);
    EXPECT_THROW(writePng(solid(2, 2, 0), "/nonexistent/throng/out.png"), std::runtime_error);
}

}  // namespace
}  // namespace throng
