#pragma once
// The APP traversal: runs every node's update callback (behaviours, animation), parents before
// children, skipping subtrees that hold no callback.

#include <cstdint>

#include "throng/scenegraph/FrameContext.h"
#include "throng/scenegraph/NodeVisitor.h"

namespace throng {

/// Runs update callbacks for one frame. Callbacks may change their node's matrix or DOFs, but not
/// the tree's structure.
class AppVisitor : public NodeVisitor {
public:
    /// Prepares a traversal for the frame `context`.
    explicit AppVisitor(const FrameContext& context) : context_(context) {}

    void apply(Node& node) override;
    void apply(Group& group) override;

    /// Number of callbacks run so far.
    std::uint64_t callbacksRun() const { return callbacksRun_; }
    /// The frame being processed.
    const FrameContext& context() const { return context_; }

private:
    void runCallback(Node& node);
    FrameContext context_;
    std::uint64_t callbacksRun_ = 0;
};

}  // namespace throng
