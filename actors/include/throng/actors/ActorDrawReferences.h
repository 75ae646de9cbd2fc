#pragma once
// The numbering of what the draw items of a crowd's actors point to (DrawReferences), made the
// same way by every process that builds the same scene, so that a process posing some of the
// actors can send the drawing process its items as records (DrawRecords.h).

#include "throng/scenegraph/DrawReferences.h"

namespace throng {

class ActorProcessor;
class Crowd;
class Node;

/// Numbers, in this order: the nodes of `crowd` under `root` in the order a traversal meets them
/// (so that merged records keep one process's order); then, template by template in order of
/// their first actor, the template's vaLod drawables (the actor's own, then each Skeleton
/// node's), the impostor `processor` shows for it and its key-pose cache there; then the drawables
/// actors hold, actor by actor.
DrawReferences actorDrawReferences(const Crowd& crowd, Node& root, const ActorProcessor& processor);

}  // namespace throng
