#pragma once
// Base of every scenegraph node: a name, a parent, an optional APP callback and the world-space
// bounding sphere cached by the last matrices-and-bounds pass. Nodes form a tree (one parent each);
// clones share Drawables, not nodes.

#include <cstddef>
#include <memory>
#include <string>

#include "throng/scenegraph/BoundingSphere.h"

namespace throng {

class Group;
class NodeVisitor;
class UpdateCallback;

/// A node of the scene tree.
class Node {
public:
    Node();
    virtual ~Node();
    Node(const Node&) = delete;
    Node& operator=(const Node&) = delete;

    /// Dispatches to the visitor's apply() overload for this node's type.
    virtual void accept(NodeVisitor& visitor);

    /// Name used in statistics and error messages.
    const std::string& name() const { return name_; }
    /// Sets the name.
    void setName(std::string name) { name_ = std::move(name); }

    /// The group holding this node, or null for a root.
    Group* parent() const { return parent_; }

    /// Sets (or clears, with null) the callback the APP traversal runs on this node.
    void setUpdateCallback(std::shared_ptr<UpdateCallback> callback);
    /// The APP callback, or null.
    UpdateCallback* updateCallback() const { return updateCallback_.get(); }
    /// Number of nodes in this subtree (this one included) with an APP callback; APP skips zeros.
    std::size_t updateCallbackCount() const { return updateCallbackCount_; }

    /// World-space bounding sphere from the last matrices-and-bounds pass (empty before it).
    const BoundingSphere& worldBound() const { return worldBound_; }
    /// Whether this subtree changed since its bound was last computed.
    bool boundDirty() const { return boundDirty_; }
    /// Marks this node and its ancestors as needing their bounds recomputed.
    void dirtyBound();

protected:
    friend class Group;
    friend class MatrixBoundsVisitor;
    /// Adds `delta` to the callback count of this node and its ancestors.
    void adjustUpdateCallbackCount(std::ptrdiff_t delta);

    BoundingSphere worldBound_;
    bool boundDirty_ = true;
    bool worldStale_ = true;  // the frame above this node changed untracked (new parent)

private:
    std::string name_;
    Group* parent_ = nullptr;
    std::shared_ptr<UpdateCallback> updateCallback_;
    std::size_t updateCallbackCount_ = 0;
};

}  // namespace throng
