#pragma once
// The interface actor-aware traversals (ActorProcessor's) offer to Actor and ActorGroup nodes
// through NodeVisitor::extension. A node visited by a traversal without it is processed the
// traditional way, like any generic node.

#include <span>

#include "throng/actors/ActorId.h"
#include "throng/scenegraph/BoundingSphere.h"

namespace throng {

class CullVisitor;
class MatrixBoundsVisitor;
class Node;

/// Actor processing's handling of the nodes that stand for actors.
class ActorTraversal {
public:
    /// The key under which traversals register this interface.
    static const char kKey;

    virtual ~ActorTraversal() = default;
    /// Matrices and bounds: places the actors `ids` of `node` in the world; returns the node's bound
    /// (`roaming` when valid and it holds them all: ActorGroup::setRoamingBound).
    virtual BoundingSphere bound(Node& node, std::span<const ActorId> ids, MatrixBoundsVisitor& visitor,
                                 const BoundingSphere& roaming = {}) = 0;
    /// CULL: `node`'s bound passed; takes its actors `ids` into the actor culling cascade.
    /// `boundIsMemberSphere`: the bound is its one actor's Refpoint Bsphere, so the traversal's
    /// test was that actor's CULL 1 (not so for a group with a roaming bound).
    virtual void cull(Node& node, std::span<const ActorId> ids, CullVisitor& visitor, bool boundIsMemberSphere) = 0;
    /// CULL: `node`'s bound was outside; its actors `ids` are rejected.
    virtual void culledOut(Node& node, std::span<const ActorId> ids, CullVisitor& visitor) = 0;
};

}  // namespace throng
