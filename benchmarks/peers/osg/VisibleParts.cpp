#include "VisibleParts.h"

#include "throng/actors/Actor.h"
#include "throng/actors/ActorGroup.h"

namespace throng::peers {

std::vector<VisiblePart> visibleParts(const DrawList& list) {
    std::vector<VisiblePart> parts;
    parts.reserve(list.size());
    for (const DrawItem& item : list.items()) {
        // Draw items of actors name the node standing for them and, for a group, the member.
        if (const auto* group = dynamic_cast<const ActorGroup*>(item.node))
            parts.push_back({group->ids()[item.instance], item.part, item.lodLevel});
        else if (const auto* actor = dynamic_cast<const Actor*>(item.node))
            parts.push_back({actor->id(), item.part, item.lodLevel});
    }
    std::sort(parts.begin(), parts.end());
    return parts;
}

std::vector<ActorId> actorsOf(std::span<const VisiblePart> parts) {
    std::vector<ActorId> actors;
    for (const VisiblePart& p : parts)
        if (actors.empty() || actors.back() != p.actor) actors.push_back(p.actor);
    return actors;
}

}  // namespace throng::peers
