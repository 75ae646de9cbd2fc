#include "throng/render/ImageIO.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include <stb_image.h>
#include <stb_image_write.h>

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
    errno = 0;
    if (!stbi_write_png(path.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4))
        throw std::runtime_error("writePng: cannot write '" + path.string() + "'" +
                                 (errno ? std::string(": ") + std::strerror(errno) : std::string()));
}

}  // namespace throng
