#pragma once
// The CPU reference of how the impostor passes recolour a cell baked with kBakeLook: each texel
// times the actor's colour of the body region the cell shows there, in linear light. The quality
// tool measures cells as throng-town shows them with it; the GL passes are tested against it.

#include <cstdint>
#include <span>

#include "throng/scenegraph/BodyLook.h"
#include "throng/scenegraph/Image.h"

namespace throng {

/// `cell` (premultiplied sRGB RGBA8) recoloured by `look` where `regions` (one BodyRegion per
/// texel, top row first) says: the colour decoded to linear, times the look's linear colour of the
/// region (white for none, or a colour with alpha 0), encoded again; alpha kept. Throws
/// std::invalid_argument if `regions` does not have one value per texel.
Image applyBodyLook(const Image& cell, std::span<const std::uint8_t> regions, const BodyLook& look);

}  // namespace throng
