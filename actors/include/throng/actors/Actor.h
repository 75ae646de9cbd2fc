#pragma once
// The Actor node (seed 002 §3): stands for one actor of a Crowd in a scenegraph. It holds no state
// itself (the Crowd does) and takes part in traversals like any node: traditional traversals
// process its skeleton the generic way; ActorProcessor's run the culling cascade.

#include "throng/actors/ActorId.h"
#include "throng/scenegraph/Node.h"

namespace throng {

class Crowd;

/// A scenegraph node for one actor.
class Actor : public Node {
public:
    /// Made by Crowd::makeActorNode.
    Actor(Crowd& crowd, ActorId id);
    /// Hands its actors back to the crowd (they stay, held by no node).
    ~Actor() override;

    /// The crowd holding the actor's state.
    Crowd& crowd() const { return *crowd_; }
    /// The actor.
    ActorId id() const { return id_; }

    void traverseApp(AppVisitor& visitor) override;
    void updateMatricesAndBound(MatrixBoundsVisitor& visitor) override;
    void traverseCull(CullVisitor& visitor) override;
    void culledOut(CullVisitor& visitor) override;

private:
    Crowd* crowd_;
    ActorId id_;
};

}  // namespace throng
