#pragma once
// An RGBA8 image in memory: textures, impostor atlases, rendered frames.

#include <cstdint>
#include <string>
#include <vector>

namespace throng {

/// Pixels as rows of RGBA8, top row first.
struct Image {
    std::string name;                 ///< where it came from, for messages
    int width = 0;                    ///< pixels
    int height = 0;                   ///< pixels
    std::vector<std::uint8_t> rgba;   ///< width * height * 4 bytes

    /// Whether the size and the pixel buffer agree and are non-empty.
    bool valid() const {
        return width > 0 && height > 0 && rgba.size() == static_cast<std::size_t>(width) * height * 4;
    }
};

}  // namespace throng
