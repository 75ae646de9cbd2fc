#pragma once
// Double dispatch over node types, as in the VulkanSceneGraph: a traversal overrides apply() for
// the types it cares about; the defaults visit every child in order.

namespace throng {

class Node;
class Group;
class Transform;
class LOD;
class Geometry;
class Occluder;

/// Visits nodes by type. Types added by other libraries dispatch to the closest base overload.
class NodeVisitor {
public:
    virtual ~NodeVisitor() = default;
    /// Any node; the default does nothing.
    virtual void apply(Node& node);
    /// A group; the default visits every child.
    virtual void apply(Group& group);
    /// A transform; the default calls apply(Group&).
    virtual void apply(Transform& transform);
    /// An LOD; the default calls apply(Group&).
    virtual void apply(LOD& lod);
    /// A geometry leaf; the default calls apply(Node&).
    virtual void apply(Geometry& geometry);
    /// An occluder declaration; the default calls apply(Node&).
    virtual void apply(Occluder& occluder);

    /// Visits every child of `group` in order.
    void traverse(Group& group);

    /// The interface this visitor offers node types of other libraries under `key` (the address of
    /// a constant that library defines), or null. Lets such a node find, say, an actor-aware
    /// traversal without RTTI: one compare per node.
    void* extension(const void* key) const { return key == extensionKey_ ? extension_ : nullptr; }

protected:
    /// Registers `extension` under `key` (one per visitor).
    void setExtension(const void* key, void* extension) {
        extensionKey_ = key;
        extension_ = extension;
    }

private:
    const void* extensionKey_ = nullptr;
    void* extension_ = nullptr;
};

}  // namespace throng
