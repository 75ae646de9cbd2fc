#pragma once
// Internal to actors: the draw item of one part of an actor, and a skin palette computed into the
// crowd's frame arena. Both processing methods make their items with these, so they agree.

#include <span>

#include "throng/actors/Crowd.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/DrawList.h"

namespace throng::detail {

/// The item drawing `drawable` for part `part` of the actor `member` of `node`.
inline DrawItem actorPartItem(const Node* node, std::uint32_t member, const glm::vec4& tint, const Drawable& drawable,
                              const Mat4* world, std::uint32_t part, int level, const glm::mat4* palette = nullptr,
                              std::size_t paletteSize = 0) {
    DrawItem item;
    item.node = node;
    item.instance = member;
    item.tint = tint;
    item.drawable = &drawable;
    item.worldMatrix = world;
    item.part = part;
    item.lodLevel = static_cast<std::uint32_t>(level);
    item.skinPalette = palette;
    item.skinPaletteSize = static_cast<std::uint32_t>(paletteSize);
    return item;
}

/// `skin`'s palette for the pose `model` (nodes flagged in `active`; all when empty), stored in the
/// crowd's arena until the next frame.
inline const glm::mat4* skinPaletteOf(Crowd& crowd, const ActorTemplate& tmpl, const Skin& skin,
                                      std::span<const Affine> model, std::span<const std::uint8_t> active, OpTally* ops) {
    glm::mat4* palette = crowd.skinPalettes().allocate(skin.joints.size());
    computeSkinPalette(tmpl, skin, model, active, std::span<glm::mat4>(palette, skin.joints.size()), ops);
    return palette;
}

}  // namespace throng::detail
