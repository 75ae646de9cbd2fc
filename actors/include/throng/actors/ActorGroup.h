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

    void traverseApp(AppVisitor& visitor) override;
    void updateMatricesAndBound(MatrixBoundsVisitor& visitor) override;
    void traverseCull(CullVisitor& visitor) override;
    void culledOut(CullVisitor& visitor) override;

private:
    Crowd* crowd_;
    std::vector<ActorId> ids_;
};

}  // namespace throng
