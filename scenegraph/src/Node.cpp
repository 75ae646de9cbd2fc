#include "throng/scenegraph/Node.h"

#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/NodeVisitor.h"
#include "throng/scenegraph/UpdateCallback.h"

namespace throng {

Node::Node() = default;
Node::~Node() = default;

void Node::accept(NodeVisitor& visitor) { visitor.apply(*this); }

void Node::setUpdateCallback(std::shared_ptr<UpdateCallback> callback) {
    const std::ptrdiff_t before = updateCallback_ ? 1 : 0;
    const std::ptrdiff_t after = callback ? 1 : 0;
    updateCallback_ = std::move(callback);
    if (after != before) adjustUpdateCallbackCount(after - before);
}

void Node::adjustUpdateCallbackCount(std::ptrdiff_t delta) {
    for (Node* n = this; n; n = n->parent_)
        n->updateCallbackCount_ = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(n->updateCallbackCount_) + delta);
}

void Node::dirtyBound() {
    for (Node* n = this; n && !n->boundDirty_; n = n->parent_) n->boundDirty_ = true;
}

}  // namespace throng
