#include "throng/scenegraph/Node.h"

#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/NodeVisitor.h"
#include "throng/scenegraph/UpdateCallback.h"

namespace throng {

Node::Node() = default;
Node::~Node() = default;

void Node::accept(NodeVisitor& visitor) { visitor.apply(*this); }

void Node::traverseApp(AppVisitor&) {}
void Node::updateMatricesAndBound(MatrixBoundsVisitor&) { worldBound_ = BoundingSphere(); }
void Node::traverseCull(CullVisitor&) {}
void Node::culledOut(CullVisitor&) {}

void Node::setUpdateCallback(std::shared_ptr<UpdateCallback> callback) {
    const std::ptrdiff_t before = (updateCallback_ || needsApp_) ? 1 : 0;
    updateCallback_ = std::move(callback);
    const std::ptrdiff_t after = (updateCallback_ || needsApp_) ? 1 : 0;
    if (after != before) adjustAppNodeCount(after - before);
}

void Node::setNeedsApp(bool needs) {
    const std::ptrdiff_t before = (updateCallback_ || needsApp_) ? 1 : 0;
    needsApp_ = needs;
    const std::ptrdiff_t after = (updateCallback_ || needsApp_) ? 1 : 0;
    if (after != before) adjustAppNodeCount(after - before);
}

void Node::adjustAppNodeCount(std::ptrdiff_t delta) {
    for (Node* n = this; n; n = n->parent_)
        n->appNodeCount_ = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(n->appNodeCount_) + delta);
}

void Node::dirtyBound() {
    for (Node* n = this; n && !n->boundDirty_; n = n->parent_) n->boundDirty_ = true;
}

}  // namespace throng
