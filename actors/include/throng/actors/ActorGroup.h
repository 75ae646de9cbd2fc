#pragma once
// A node standing for many actors of a Crowd, culled first as a group (the group bounding sphere
// the seed's conclusion asks for, for crowds and flocks); the survivors go through the cascade in
// flat arrays. Traditional traversals process every member the generic way.

#include <span>
#include <vector>

#include "throng/actors/ActorId.h"
#include "throng/scenegraph/Node.h"

namespace throng {

class Crowd;

/// A scenegraph node for a set of actors.
class ActorGroup : public Node {
public:
    /// Made by Crowd::makeGroupNode.
    ActorGroup(Crowd& crowd, std::vector<ActorId> ids);
    /// Hands its actors back to the crowd (they stay, held by no node).
    ~ActorGroup() override;

    /// The crowd holding the actors' state.
    Crowd& crowd() const { return *crowd_; }
    /// The actors, in order (DrawItem::instance indexes this list).
    std::span<const ActorId> ids() const { return ids_; }

    /// Declares that every member's Refpoint Bsphere stays inside `bound` wherever the members go
    /// (in the group's parent frame; for walkers, their walkable area): actor processing then
    /// takes it as the group's bound instead of growing one over the members every frame. Such a
    /// bound does not depend on where the members are, so processes that each hold some of them
    /// agree on it. A member found outside still widens it for that frame (culling stays
    /// conservative). An empty sphere (the default) grows the bound over the members.
    void setRoamingBound(const BoundingSphere& bound) { roamingBound_ = bound; }
    /// The declared roaming bound, empty when none.
    const BoundingSphere& roamingBound() const { return roamingBound_; }

    void traverseApp(AppVisitor& visitor) override;
    void updateMatricesAndBound(MatrixBoundsVisitor& visitor) override;
    void traverseCull(CullVisitor& visitor) override;
    void culledOut(CullVisitor& visitor) override;

private:
    Crowd* crowd_;
    std::vector<ActorId> ids_;
    BoundingSphere roamingBound_;
};

}  // namespace throng
