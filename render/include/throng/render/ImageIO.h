#pragma once
// PNG files to and from throng::Image (RGBA8, top row first), through Debian's libstb.

#include <filesystem>

#include "throng/scenegraph/Image.h"

namespace throng {

/// Reads a PNG (any bit depth and channel count, converted to RGBA8). The image is named after
/// the file. Throws std::runtime_error naming the file and the decoder's reason on failure.
Image readPng(const std::filesystem::path& path);

/// Writes `image` as an RGBA PNG. Throws std::invalid_argument if the image is not valid() and
/// std::runtime_error naming the file if it cannot be written.
void writePng(const Image& image, const std::filesystem::path& path);

}  // namespace throng
