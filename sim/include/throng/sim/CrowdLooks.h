#pragma once
// Looks for a crowd that does not look cloned (BodyLook: a colour per body region): generated from
// palettes of skin tones, hair colours and clothes, or written in the scene file, and handed to
// each actor of a group so that neighbours differ.

#include <cstdint>
#include <string>
#include <vector>

#include "throng/scenegraph/BodyLook.h"

namespace throng::sim {

/// `count` (1-240) distinct looks from built-in palettes (six skin tones, six hair colours, ten
/// tops, eight bottoms), the same for the same count. Throws std::invalid_argument out of range.
std::vector<BodyLook> generatedLooks(int count);

/// The look actor `index` of group `group` wears among `looks` (not empty): a hash of both, so
/// neighbours in a group and the groups' first actors differ.
const BodyLook& lookForActor(const std::vector<BodyLook>& looks, std::size_t group, std::size_t index);

/// Reads "#rrggbb" (hex digits, any case) as a packed opaque BodyLook colour. Throws
/// std::invalid_argument naming `text` otherwise.
std::uint32_t parseBodyColour(const std::string& text);

}  // namespace throng::sim
