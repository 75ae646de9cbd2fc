#pragma once
// A node with ordered children. Traversals visit children in the order they were added.

#include <memory>
#include <vector>

#include "throng/scenegraph/Node.h"

namespace throng {

/// A node holding an ordered list of children it owns (shared ownership with the caller).
class Group : public Node {
public:
    /// An empty group (it may hold occluders until its bound is first merged).
    Group() { mayHoldOccluders_ = true; }

    void accept(NodeVisitor& visitor) override;

    /// Appends `child`. Throws std::invalid_argument if it is null, already has a parent, or is
    /// this group or one of its ancestors (which would make a cycle).
    void addChild(std::shared_ptr<Node> child);
    /// Removes `child` if present; returns whether it was.
    bool removeChild(const Node* child);
    /// Number of children.
    std::size_t childCount() const { return children_.size(); }
    /// Child `i` (throws std::out_of_range if i >= childCount()).
    Node& child(std::size_t i) const;
    /// The children, in order.
    const std::vector<std::shared_ptr<Node>>& children() const { return children_; }

private:
    std::vector<std::shared_ptr<Node>> children_;
};

}  // namespace throng
