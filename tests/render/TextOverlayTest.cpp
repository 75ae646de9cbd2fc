// Text over a frame: the overlay's letters land where asked, in the colour asked, over a panel.

#include <gtest/gtest.h>

#include "throng/render/ContextFactory.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/ImageOverlay.h"
#include "throng/render/TextOverlay.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"

using namespace throng;

TEST(TextOverlay, DrawsTextWhereAsked) {
    auto context = createContext({.width = 240, .height = 80});
    GlRenderer renderer(context);
    TextOverlay overlay(*context);
    renderer.beginFrame(Camera());
    renderer.draw(DrawList());
    overlay.draw("Throng 42", 10, 10, 2.0f, glm::vec4(1, 0, 0, 1));
    const Image frame = renderer.readFrame();
    ASSERT_EQ(frame.width, 240);
    const std::uint8_t* corner = &frame.rgba[std::size_t((frame.height - 1) * frame.width + frame.width - 1) * 4];  // background
    int red = 0, redOutside = 0, dark = 0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            const std::uint8_t* p = &frame.rgba[std::size_t(y * frame.width + x) * 4];
            const bool isRed = p[0] > 200 && p[1] < 60 && p[2] < 60;
            const bool inBox = x >= 10 && x < 10 + 9 * 6 * 2 && y >= 10 && y < 10 + 12 * 2;
            red += isRed && inBox;
            redOutside += isRed && !inBox;
            dark += p[2] + 60 < corner[2] && !isRed;  // clearly darker than the background
        }
    EXPECT_GT(red, 100) << "letters drawn";
    EXPECT_EQ(redOutside, 0) << "only where asked";
    EXPECT_GT(dark, 200) << "over a translucent panel";
}

// An image overlay lands where asked, at the size asked, top row at the top.
TEST(ImageOverlay, DrawsAnImageWhereAskedTopRowUp) {
    auto context = createContext({.width = 200, .height = 100});
    GlRenderer renderer(context);
    ImageOverlay overlay(*context);
    Image image;
    image.name = "two rows";
    image.width = 2;
    image.height = 2;
    image.rgba = {255, 0, 0, 255, 255, 0, 0, 255,    // top row red
                  0, 0, 255, 255, 0, 0, 255, 255};  // bottom row blue
    renderer.beginFrame(Camera());
    renderer.draw(DrawList());
    overlay.draw(image, 100, 20, 80, 60);
    const Image frame = renderer.readFrame();
    const auto at = [&](int x, int y) { return &frame.rgba[std::size_t(y * frame.width + x) * 4]; };
    EXPECT_GT(at(140, 35)[0], 200);  // upper half of the rectangle: red
    EXPECT_LT(at(140, 35)[2], 60);
    EXPECT_GT(at(140, 65)[2], 200);  // lower half: blue
    EXPECT_LT(at(140, 65)[0], 60);
    for (const auto& [x, y] : {std::pair{95, 50}, std::pair{185, 50}, std::pair{140, 15}, std::pair{140, 85}}) {
        const std::uint8_t* p = at(x, y);  // outside: the background
        EXPECT_FALSE((p[0] > 200 && p[2] < 60) || (p[2] > 200 && p[0] < 60)) << x << ", " << y;
    }
    Image broken = image;
    broken.rgba.pop_back();
    EXPECT_THROW(overlay.draw(broken, 0, 0, 10, 10), std::invalid_argument);
}
