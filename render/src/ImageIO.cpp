#include "throng/render/ImageIO.h"

#include <stdexcept>
#include <string>

#include <stb_image.h>
#include <stb_image_write.h>

#include "throng/scenegraph/WholeFile.h"

namespace throng {

Image readPng(const std::filesystem::path& path) {
    int width = 0, height = 0, channels = 0;
    unsigned char* pixels = stbi_load(path.c_str(), &width, &height, &channels, 4);
    if (!pixels) {
        const char* reason = stbi_failure_reason();
        throw std::runtime_error("readPng: cannot read '" + path.string() + "': " + (reason ? reason : "unknown error"));
    }
    Image image;
    image.name = path.string();
    image.width = width;
    image.height = height;
    image.rgba.assign(pixels, pixels + static_cast<std::size_t>(width) * height * 4);
    stbi_image_free(pixels);
    return image;
}

void writePng(const Image& image, const std::filesystem::path& path) {
    if (!image.valid())
        throw std::invalid_argument("writePng: image '" + image.name + "' is not valid (" + std::to_string(image.width) +
                                    " x " + std::to_string(image.height) + ", " + std::to_string(image.rgba.size()) +
                                    " bytes) for '" + path.string() + "'");
    // Encoded in memory, then written whole: a PNG is either all there or absent.
    std::string encoded;
    const auto append = [](void* into, void* data, int size) { static_cast<std::string*>(into)->append(static_cast<const char*>(data), std::size_t(size)); };
    if (!stbi_write_png_to_func(append, &encoded, image.width, image.height, 4, image.rgba.data(), image.width * 4))
        throw std::runtime_error("writePng: cannot encode '" + path.string() + "'");
    try {
        writeWholeFile(path, encoded);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string("writePng: ") + e.what());
    }
}

}  // namespace throng
