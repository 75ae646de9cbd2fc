#include "throng/render/BodyLookImage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace throng {
namespace {

float toLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
float toSrgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c < 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

Image applyBodyLook(const Image& cell, std::span<const std::uint8_t> regions, const BodyLook& look) {
    const std::size_t texels = static_cast<std::size_t>(cell.width) * static_cast<std::size_t>(cell.height);
    if (regions.size() != texels)
        throw std::invalid_argument("applyBodyLook: " + std::to_string(regions.size()) + " regions for " + std::to_string(texels) + " texels");
    // Each region's linear colour (white: kept).
    std::array<std::array<float, 3>, kBodyRegionCount + 1> paint{};
    for (std::size_t r = 0; r <= kBodyRegionCount; ++r) {
        const std::uint32_t c = r == 0 ? 0u : look.rgba[r - 1];
        for (int k = 0; k < 3; ++k) paint[r][static_cast<std::size_t>(k)] = c >> 24 ? toLinear(static_cast<float>((c >> (8 * k)) & 255u) / 255.0f) : 1.0f;
    }
    Image out = cell;
    for (std::size_t i = 0; i < texels; ++i) {
        const std::uint8_t a = cell.rgba[i * 4 + 3];
        if (a == 0 || regions[i] == 0 || regions[i] > kBodyRegionCount) continue;
        const float alpha = static_cast<float>(a) / 255.0f;
        for (std::size_t k = 0; k < 3; ++k) {
            const float straight = static_cast<float>(cell.rgba[i * 4 + k]) / 255.0f / alpha;  // premultiplied in the cell
            const float shown = toSrgb(toLinear(std::min(straight, 1.0f)) * paint[regions[i]][k]) * alpha;
            out.rgba[i * 4 + k] = static_cast<std::uint8_t>(std::lround(std::clamp(shown, 0.0f, 1.0f) * 255.0f));
        }
    }
    return out;
}

}  // namespace throng
