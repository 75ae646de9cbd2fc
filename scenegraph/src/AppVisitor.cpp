#include "throng/scenegraph/AppVisitor.h"

#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/UpdateCallback.h"

namespace throng {

void AppVisitor::runCallback(Node& node) {
    if (UpdateCallback* cb = node.updateCallback()) {
        cb->update(node, context_);
        ++callbacksRun_;
    }
}

void AppVisitor::apply(Node& node) {
    runCallback(node);
    node.traverseApp(*this);
}

void AppVisitor::apply(Group& group) {
    if (group.appNodeCount() == 0) return;
    runCallback(group);
    for (const auto& child : group.children())
        if (child->appNodeCount() != 0) child->accept(*this);
}

}  // namespace throng
