#pragma once
// Resource limits of the glTF loader: files come from users and the network, so a hostile or
// broken file must fail with an error, not exhaust memory or the stack.

#include <cstddef>
#include <cstdint>

namespace throng {

/// Upper bounds checked while loading (exceeding one is a GltfError naming the value).
struct GltfLimits {
    std::uint64_t maxFileBytes = 512ull << 20;       ///< the file itself and each external buffer or image
    std::uint64_t maxAccessorValues = 64ull << 20;   ///< components read from one accessor (count x width)
    std::uint64_t maxImagePixels = 64ull << 20;      ///< width x height of one decoded image
    int maxJsonDepth = 64;                           ///< nesting of JSON arrays and objects
    double maxClipDuration = 24.0 * 3600.0;          ///< seconds, last key time of an animation
};

}  // namespace throng
