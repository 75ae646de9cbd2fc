#include "throng/scenegraph/Group.h"

#include <algorithm>
#include <stdexcept>

#include "throng/scenegraph/NodeVisitor.h"
#include "throng/scenegraph/Validation.h"

namespace throng {

void Group::accept(NodeVisitor& visitor) { visitor.apply(*this); }

void Group::addChild(std::shared_ptr<Node> child) {
    auto where = [this] { return errorContext("Group::addChild", name()); };
    if (!child) throw std::invalid_argument(where() + ": argument 'child' is null");
    if (child->parent_)
        throw std::invalid_argument(where() + ": child '" + child->name() + "' already has a parent ('" +
                                    child->parent_->name() + "')");
    for (const Node* n = this; n; n = n->parent_)
        if (n == child.get())
            throw std::invalid_argument(where() + ": child '" + child->name() +
                                        "' is this group or one of its ancestors");
    child->parent_ = this;
    child->worldStale_ = true;
    child->boundDirty_ = true;
    const std::size_t callbacks = child->appNodeCount();
    children_.push_back(std::move(child));
    if (callbacks) adjustAppNodeCount(static_cast<std::ptrdiff_t>(callbacks));
    boundDirty_ = false;  // force dirtyBound() to propagate from here
    dirtyBound();
}

bool Group::removeChild(const Node* child) {
    auto it = std::find_if(children_.begin(), children_.end(),
                           [child](const std::shared_ptr<Node>& c) { return c.get() == child; });
    if (it == children_.end()) return false;
    const std::size_t callbacks = (*it)->appNodeCount();
    (*it)->parent_ = nullptr;
    (*it)->dirtyBound();
    children_.erase(it);
    if (callbacks) adjustAppNodeCount(-static_cast<std::ptrdiff_t>(callbacks));
    boundDirty_ = false;
    dirtyBound();
    return true;
}

Node& Group::child(std::size_t i) const {
    if (i >= children_.size())
        throw std::out_of_range(errorContext("Group::child", name()) + ": index " + std::to_string(i) +
                                " is out of range (" + std::to_string(children_.size()) + " children)");
    return *children_[i];
}

}  // namespace throng
