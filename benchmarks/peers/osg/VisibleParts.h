#pragma once
// What a method sent to be drawn, reduced to (actor, part, level of detail) so that Throng's draw
// lists and OpenSceneGraph's render bins can be compared: the visible-actor check of the peer
// benchmark. Parts are numbered as Throng's draw items number them: Skeleton node i is part i,
// the actor-level geometry is part nodeCount().

#include <algorithm>
#include <compare>
#include <cstdint>
#include <span>
#include <vector>

#include "throng/actors/ActorId.h"
#include "throng/scenegraph/DrawList.h"

namespace throng::peers {

/// One part of one actor, drawn at one level of its vaLod.
struct VisiblePart {
    ActorId actor = 0;        ///< the actor
    std::uint32_t part = 0;   ///< Skeleton node index, or the template's node count for the actor-level geometry
    std::uint32_t level = 0;  ///< vaLod level index (levels showing nothing count too)

    /// Ordered by actor, then part, then level.
    auto operator<=>(const VisiblePart&) const = default;
};

/// The actor parts in a Throng draw list, sorted (items of generic nodes are left out).
std::vector<VisiblePart> visibleParts(const DrawList& list);

/// The actors of sorted `parts`, sorted and unique.
std::vector<ActorId> actorsOf(std::span<const VisiblePart> parts);

/// Elements of one sorted set missing from another.
template <class T>
struct SetDifference {
    std::vector<T> onlyInFirst;   ///< in the first set, not in the second
    std::vector<T> onlyInSecond;  ///< in the second set, not in the first
    /// Whether the sets are equal.
    bool empty() const { return onlyInFirst.empty() && onlyInSecond.empty(); }
};

/// The difference of two sorted sets.
template <class T>
SetDifference<T> difference(std::span<const T> first, std::span<const T> second) {
    SetDifference<T> d;
    std::set_difference(first.begin(), first.end(), second.begin(), second.end(), std::back_inserter(d.onlyInFirst));
    std::set_difference(second.begin(), second.end(), first.begin(), first.end(), std::back_inserter(d.onlyInSecond));
    return d;
}

}  // namespace throng::peers
