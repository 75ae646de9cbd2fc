#pragma once
// Internal to actors: the Skeleton node a held object is drawn with.

#include <cstdint>
#include <span>

#include "throng/actors/ActorTemplate.h"

namespace throng::cascade {

/// The node a held object on `node` is drawn with: `node` itself, or its nearest active ancestor
/// (-1 when none is active: the object follows the Skeleton Root).
inline int holderNode(const ActorTemplate& t, std::span<const std::uint8_t> active, int node) {
    while (node >= 0 && !active[static_cast<std::size_t>(node)]) node = t.nodes()[static_cast<std::size_t>(node)].parent;
    return node;
}

}  // namespace throng::cascade
