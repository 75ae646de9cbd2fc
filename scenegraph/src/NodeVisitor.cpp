#include "throng/scenegraph/NodeVisitor.h"

#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/Occluder.h"
#include "throng/scenegraph/Transform.h"

namespace throng {

void NodeVisitor::apply(Node&) {}
void NodeVisitor::apply(Group& group) { traverse(group); }
void NodeVisitor::apply(Transform& transform) { apply(static_cast<Group&>(transform)); }
void NodeVisitor::apply(LOD& lod) { apply(static_cast<Group&>(lod)); }
void NodeVisitor::apply(Geometry& geometry) { apply(static_cast<Node&>(geometry)); }
void NodeVisitor::apply(Occluder& occluder) { apply(static_cast<Node&>(occluder)); }

void NodeVisitor::traverse(Group& group) {
    for (const auto& child : group.children()) child->accept(*this);
}

}  // namespace throng
