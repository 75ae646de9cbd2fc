#pragma once
// Crowd diversity (seed 000 §2, after Tecchia et al.): a template's vertices each belong to a body
// region (skin, hair, top, bottom), and every actor carries its own colour per region. The skinned
// mesh, the key-pose rows and the impostor (whose atlas bakes the regions as a mask) all recolour
// the same way, so one actor keeps its colours at every tier and no atlas is baked per colour.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace throng {

/// The body region of a vertex. None keeps the material's own colour.
enum class BodyRegion : std::uint8_t { None = 0, Skin = 1, Hair = 2, Top = 3, Bottom = 4 };

/// Number of recolourable regions (Skin ... Bottom).
inline constexpr std::size_t kBodyRegionCount = 4;

/// The region's name as scene files spell it ("skin", "hair", "top", "bottom"; "none").
constexpr std::string_view bodyRegionName(BodyRegion region) {
    switch (region) {
    case BodyRegion::Skin: return "skin";
    case BodyRegion::Hair: return "hair";
    case BodyRegion::Top: return "top";
    case BodyRegion::Bottom: return "bottom";
    default: return "none";
    }
}

/// One actor's colours, one per region (Skin first), each sRGB RGBA8 packed as R | G << 8 | B << 16
/// | A << 24. A region whose alpha is 0 keeps the material's colour; otherwise its albedo becomes the
/// colour times a grey taken from the albedo's luminance (bodyRecolourGrey), so the texture's
/// light and dark stay and its hue goes. All zero (the default): the actor looks as modelled.
struct BodyLook {
    std::array<std::uint32_t, kBodyRegionCount> rgba{};  ///< packed sRGB colours, Skin, Hair, Top, Bottom

    /// Whether any region is recoloured.
    bool any() const { return (rgba[0] | rgba[1] | rgba[2] | rgba[3]) >> 24 != 0; }
    /// Two looks are equal when every region has the same colour.
    friend bool operator==(const BodyLook&, const BodyLook&) = default;
};

/// Packs an opaque sRGB colour (0-255 per channel).
constexpr std::uint32_t packBodyColour(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    return std::uint32_t{r} | std::uint32_t{g} << 8 | std::uint32_t{b} << 16 | 0xff000000u;
}

/// The look that recolours every region white: impostor atlases are baked with it, so that the
/// draw can multiply each region by the actor's own colour.
inline constexpr BodyLook kBakeLook{{packBodyColour(255, 255, 255), packBodyColour(255, 255, 255),
                                     packBodyColour(255, 255, 255), packBodyColour(255, 255, 255)}};

/// The grey a recoloured albedo keeps from linear luminance `luminance`: 0.3 + 1.4 * luminance,
/// clamped to [0, 1] (shaders use the same formula; a mid-grey texture shows the colour as given).
constexpr float bodyRecolourGrey(float luminance) {
    const float g = 0.3f + 1.4f * luminance;
    return g < 0.0f ? 0.0f : g > 1.0f ? 1.0f : g;
}

}  // namespace throng
