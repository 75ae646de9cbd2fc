#pragma once
// Work attached to a node and run by the APP traversal each frame (behaviours, animation).

#include "throng/scenegraph/FrameContext.h"

namespace throng {

class Node;

/// Called once per frame by the APP traversal, before the node's children are visited.
class UpdateCallback {
public:
    virtual ~UpdateCallback() = default;
    /// Updates `node` (for example sets a Transform's DOFs) for the frame in `context`.
    virtual void update(Node& node, const FrameContext& context) = 0;
};

}  // namespace throng
