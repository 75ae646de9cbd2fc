#pragma once
// Internal: texture decoding for the glTF loader. PNG goes to stb_image; JPEG goes to libjpeg-turbo,
// because the stb_image JPEG decoder Debian ships (2.27) overflows the heap on crafted input.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "throng/scenegraph/Image.h"

namespace throng::gltf {

/// Decodes PNG or JPEG `bytes` to RGBA8, refusing images of more than `maxPixels` pixels. Returns
/// nothing and sets `problem` when the data is not a supported, intact image.
std::optional<Image> decodeImage(const std::vector<std::uint8_t>& bytes, const std::string& name,
                                 std::uint64_t maxPixels, std::string& problem);

}  // namespace throng::gltf
