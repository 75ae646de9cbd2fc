#pragma once
// Traditional processing of actors (DESIGN.md, "One frame, two ways"): what a generic scenegraph
// does with an actor made of transform, LOD and geometry nodes. APP evaluates the behaviour at full
// precision for every DOF of every actor; every matrix is composed on the CPU; every internal
// sphere is recomputed bottom-up; CULL tests them hierarchically and every LOD node (one per
// Skeleton node and one for the actor) computes its own eye distance. It is the baseline.
//
// LOD centres are the actor's Skeleton Root, so that both methods choose the same detail and can be
// compared primitive for primitive; the cost is still paid once per LOD node.

#include <span>

#include "throng/actors/ActorId.h"
#include "throng/scenegraph/BoundingSphere.h"

namespace throng {

class CullVisitor;
class Crowd;
class MatrixBoundsVisitor;
class Node;
struct FrameContext;

/// APP for actors `ids`: Reference Point, Skeleton Root and every DOF at the behaviour's level 0.
void traditionalApp(Crowd& crowd, std::span<const ActorId> ids, const FrameContext& context);
/// Matrices and bounds for actors `ids` under the visitor's parent frame; returns their union.
BoundingSphere traditionalBound(Crowd& crowd, std::span<const ActorId> ids, MatrixBoundsVisitor& visitor);
/// CULL for actors `ids` of `node` (whose bound passed): hierarchical tests and per-node LOD.
/// `testEach` tests each actor's own bound first (for groups; a single actor's was the node's).
void traditionalCull(Crowd& crowd, const Node& node, std::span<const ActorId> ids, CullVisitor& visitor, bool testEach);

}  // namespace throng
