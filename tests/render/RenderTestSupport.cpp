#include "RenderTestSupport.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "throng/testkit/Cameras.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/ImageIO.h"
#include "throng/render/RendererOptions.h"

namespace throng::test {

Camera makeCamera(const Vec3& eye, const Vec3& target) {
    return testkit::lookingAt(eye, target, {std::numbers::pi / 4.0, double(kWidth) / kHeight, 0.1, 100.0});
}

void Scene::add(std::shared_ptr<const Drawable> drawable, const Mat4& world, const glm::vec4& tint,
                const std::vector<glm::mat4>* palette) {
    DrawItem item;
    item.drawable = drawable.get();
    item.world = ItemTransform(world);
    item.tint = tint;
    if (palette) {
        palettes_.push_back(*palette);
        item.skinPalette = palettes_.back().data();
        item.skinPaletteSize = static_cast<std::uint32_t>(palettes_.back().size());
    }
    list_.add(item, drawable->primitiveCount());
    drawables_.push_back(std::move(drawable));
}

Image renderFrame(GlRenderer& renderer, const Camera& camera, const Scene& scene) {
    renderer.beginFrame(camera);
    renderer.draw(scene.list());
    Image image = renderer.readFrame();
    renderer.endFrame();
    return image;
}

std::shared_ptr<const MeshDrawable> drawable(std::shared_ptr<const MeshData> mesh) {
    return std::make_shared<MeshDrawable>(std::move(mesh));
}

std::size_t coveredPixels(const Image& image) {
    const glm::vec4 c = RendererOptions{}.clearColor;
    const auto level = [](float v) { return static_cast<int>(std::lround(v * 255.0f)); };
    std::size_t n = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4)
        if (std::abs(image.rgba[i] - level(c.r)) > 2 || std::abs(image.rgba[i + 1] - level(c.g)) > 2 ||
            std::abs(image.rgba[i + 2] - level(c.b)) > 2)
            ++n;
    return n;
}

void writeOutput(const Image& image, const std::string& name) {
    std::filesystem::create_directories(THRONG_TEST_OUTPUT_DIR);
    writePng(image, std::filesystem::path(THRONG_TEST_OUTPUT_DIR) / (name + ".png"));
}

std::string compareWithGolden(const Image& actual, const std::string& name, const GoldenTolerance& tolerance) {
    const std::filesystem::path golden = std::filesystem::path(THRONG_GOLDEN_DIR) / (name + ".png");
    const char* update = std::getenv("THRONG_UPDATE_GOLDEN");
    if (update && std::string(update) == "1") {
        writePng(actual, golden);
        return {};
    }
    if (!std::filesystem::exists(golden))
        return "no golden image " + golden.string() + " (run with THRONG_UPDATE_GOLDEN=1 to create it)";
    const Image expected = readPng(golden);
    if (expected.width != actual.width || expected.height != actual.height)
        return "golden " + golden.string() + " is " + std::to_string(expected.width) + " x " +
               std::to_string(expected.height) + ", the frame " + std::to_string(actual.width) + " x " +
               std::to_string(actual.height);
    const testkit::ImageDifference d = testkit::compareImages(actual, expected, tolerance.threshold);
    if (d.fractionOverThreshold <= tolerance.maxFraction && d.psnr >= tolerance.minPsnr) return {};
    writeOutput(actual, name + "-actual");
    writeOutput(testkit::differenceImage(actual, expected), name + "-diff");
    std::ostringstream why;
    why << name << ": " << d.pixelsOverThreshold << " pixels (" << 100.0 * d.fractionOverThreshold
        << "%) differ by more than " << tolerance.threshold << " (allowed " << 100.0 * tolerance.maxFraction
        << "%), PSNR " << d.psnr << " dB (required " << tolerance.minPsnr << "), max difference "
        << d.maxChannelDifference << "; see " << THRONG_TEST_OUTPUT_DIR;
    return why.str();
}

std::string disagreement(const Image& a, const Image& b, const GoldenTolerance& t) {
    const testkit::ImageDifference d = testkit::compareImages(a, b, t.threshold);
    if (d.fractionOverThreshold <= t.maxFraction && d.psnr >= t.minPsnr) return {};
    return std::to_string(d.pixelsOverThreshold) + " pixels (" + std::to_string(100.0 * d.fractionOverThreshold) +
           "%) differ by more than " + std::to_string(t.threshold) + ", PSNR " + std::to_string(d.psnr) + " dB";
}

}  // namespace throng::test
