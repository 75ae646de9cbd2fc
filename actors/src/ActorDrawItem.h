#pragma once
// Internal to actors: the draw items of an actor's parts. Both processing methods make their items
// here, so they agree; each item says whose it is (actor id, clip and clip time), so DRAW never has
// to look back into the crowd or the scene.

#include <span>

#include "throng/actors/Crowd.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Drawable.h"

namespace throng::detail {

/// What every item of one actor shares.
struct ActorItemBase {
    const Node* node = nullptr;   ///< the node holding the actor
    std::uint32_t member = 0;     ///< its index in that node
    ActorId id = 0;               ///< the actor
    glm::vec4 tint{1.0f};         ///< its tint
    BodyLook body;                ///< its colours per body region
    std::int32_t clip = -1;       ///< the clip it plays (its behaviour's main clip)
    double clipTime = 0.0;        ///< seconds into that clip it shows at the frame's time
    const ActorTemplate* tmpl = nullptr;  ///< its template
    const float* dofs = nullptr;  ///< its DOF values (the morph weights after the skeleton's)
};

/// The shared part of actor `id`'s items at simulation time `time`.
inline ActorItemBase actorItemBase(const Crowd::State& s, ActorId id, const Node* node, std::uint32_t member, double time) {
    const Behaviour& b = *s.behaviour[id];
    return ActorItemBase{node,          member, id, s.tint[id], s.body[id], b.mainClip(s.slot[id]), b.clipTime(s.slot[id], time),
                         s.tmpl[id], s.dofs.data() + s.dofOffset[id]};
}

/// Gives `item` (a mesh item of part `part`, vaLod level `level`, of actor `a`) the actor's
/// weights of its drawable's morph targets, unless every one is zero: then it keeps the neutral
/// shape and nothing is read at draw time.
inline void attachMorphWeights(DrawSegment& segment, DrawItem& item, const ActorItemBase& a, std::uint32_t part, int level) {
    if (part > a.tmpl->nodeCount()) return;  // a held object: not part of the template
    const std::span<const std::uint32_t> channels = a.tmpl->morphChannelsOf(part, static_cast<std::size_t>(level));
    if (channels.empty()) return;
    const float* weights = a.dofs + a.tmpl->morphWeightOffset();
    bool any = false;
    for (const std::uint32_t c : channels) any = any || weights[c] != 0.0f;
    if (!any) return;
    const std::span<float> room = segment.addMorphWeights(item, channels.size());
    for (std::size_t k = 0; k < channels.size(); ++k) room[k] = weights[channels[k]];
}

/// Fills `item` (fresh from DrawSegment::emplace, whose palette it keeps) to draw `drawable` for
/// part `part` of the actor `a`, at vaLod level `level`; its transform is left to the caller.
inline void setActorPart(DrawItem& item, const ActorItemBase& a, const Drawable& drawable, std::uint32_t part, int level,
                         Representation representation = Representation::Mesh) {
    item.node = a.node;
    item.instance = a.member;
    item.tint = a.tint;
    item.look = a.body;
    item.drawable = &drawable;
    item.part = part;
    item.lodLevel = static_cast<std::uint16_t>(level);
    item.actor = a.id;
    item.representation = representation;
    item.clip = a.clip;
    item.clipTime = a.clipTime;
}

/// Appends to `segment` the item drawing `drawable` for part `part` of the actor `a` at vaLod level
/// `level`, with room for a skin palette of `paletteSize` matrices and the actor's morph weights
/// when the drawable has morph targets; returns it for the caller to place (DrawItem::world). The
/// item is written once, in place.
inline DrawItem& addActorPart(DrawSegment& segment, const ActorItemBase& a, const Drawable& drawable, std::uint32_t part,
                              int level, std::size_t paletteSize = 0, Representation representation = Representation::Mesh) {
    DrawItem& item = segment.emplace(drawable.primitiveCount(), paletteSize);
    setActorPart(item, a, drawable, part, level, representation);
    // Key-pose rows and impostors keep the neutral face.
    if (drawable.morphTargetCount() != 0 && representation == Representation::Mesh && a.tmpl)
        attachMorphWeights(segment, item, a, part, level);
    return item;
}

}  // namespace throng::detail
