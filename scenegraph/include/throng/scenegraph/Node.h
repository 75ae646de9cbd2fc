#pragma once
// Base of every scenegraph node: a name, a parent, an optional APP callback and the world-space
// bounding sphere cached by the last matrices-and-bounds pass. Nodes form a tree (one parent each);
// clones share Drawables, not nodes.

#include <cstddef>
#include <memory>
#include <string>

#include "throng/scenegraph/BoundingSphere.h"

namespace throng {

class AppVisitor;
class CullVisitor;
class Group;
class MatrixBoundsVisitor;
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
    /// Number of nodes in this subtree (this one included) that APP must visit: those with an
    /// update callback or that ask for it (setNeedsApp); APP skips subtrees where it is zero.
    std::size_t appNodeCount() const { return appNodeCount_; }

    /// World-space bounding sphere from the last matrices-and-bounds pass (empty before it).
    const BoundingSphere& worldBound() const { return worldBound_; }
    /// Whether this subtree changed since its bound was last computed.
    bool boundDirty() const { return boundDirty_; }
    /// Whether the frame above this node changed in a way no pass has seen yet (a new parent).
    bool worldStale() const { return worldStale_; }
    /// Marks this node and its ancestors as needing their bounds recomputed.
    void dirtyBound();
    /// Whether this subtree may hold an Occluder node: exact for a group once the matrices-and-bounds
    /// pass merged its bound (true before), so occlusion gathering skips subtrees without any.
    bool mayHoldOccluders() const { return mayHoldOccluders_; }

    // Hooks for node types defined outside this library (actors, ...). The standard traversals call
    // them for every node they have no overload for, so such nodes take part in traditional
    // processing like any other; the defaults do nothing (no bound, nothing drawn).

    /// APP: called after this node's update callback.
    virtual void traverseApp(AppVisitor& visitor);
    /// Matrices and bounds: must set worldBound_ (in world space) and may use the visitor's parent
    /// world matrix. Called only when the subtree is dirty or its frame changed.
    virtual void updateMatricesAndBound(MatrixBoundsVisitor& visitor);
    /// CULL: called once the node's world bound passed the frustum test.
    virtual void traverseCull(CullVisitor& visitor);
    /// CULL: called when the node's world bound was found outside the frustum.
    virtual void culledOut(CullVisitor& visitor);

protected:
    /// Makes APP visit this node (and so call traverseApp) even without an update callback.
    void setNeedsApp(bool needs);

    friend class Group;
    friend class MatrixBoundsVisitor;
    /// Adds `delta` to the APP node count of this node and its ancestors.
    void adjustAppNodeCount(std::ptrdiff_t delta);

    BoundingSphere worldBound_;      ///< world-space bound, set by the matrices-and-bounds pass
    bool boundDirty_ = true;         ///< this subtree changed since its bound was computed
    bool worldStale_ = true;         ///< the frame above this node changed untracked (new parent)
    bool mayHoldOccluders_ = false;  ///< groups and Occluders set it; groups refine it when merged

private:
    std::string name_;
    Group* parent_ = nullptr;
    std::shared_ptr<UpdateCallback> updateCallback_;
    std::size_t appNodeCount_ = 0;
    bool needsApp_ = false;
};

}  // namespace throng
