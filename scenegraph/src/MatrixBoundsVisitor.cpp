#include "throng/scenegraph/MatrixBoundsVisitor.h"

#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/scenegraph/Transform.h"

namespace throng {
namespace {
const Mat4 kIdentity(1.0);
}

bool MatrixBoundsVisitor::parentIsIdentity() const { return parentWorld_ == &kIdentity; }

MatrixBoundsVisitor::MatrixBoundsVisitor(OpCounter* counter, bool fullRecompute)
    : counter_(counter), fullRecompute_(fullRecompute), parentWorld_(&kIdentity) {}

void MatrixBoundsVisitor::apply(Node& node) {
    // Node types of other libraries compute their own matrices and bound.
    if (!needsVisit(node)) return;
    node.updateMatricesAndBound(*this);
    node.boundDirty_ = false;
    node.worldStale_ = false;
}

void MatrixBoundsVisitor::mergeChildren(Group& group) {
    OpTally* ops = counter_ ? counter_->tally(OpCategory::BsphereRecompute) : nullptr;
    BoundingSphere bound;
    bool occluders = false;
    for (const auto& child : group.children()) {
        // A child well inside the bound so far leaves it unchanged: no square root (when counting,
        // every child goes through expandBy as the cost model prices it).
        if (ops || !bound.clearlyContains(child->worldBound())) bound.expandBy(child->worldBound(), ops);
        occluders = occluders || child->mayHoldOccluders_;
    }
    group.worldBound_ = bound;
    group.mayHoldOccluders_ = occluders;
    group.boundDirty_ = false;
    ++stats_.spheresRecomputed;
    if (counter_) counter_->countOperations(OpCategory::BsphereRecompute);
}

void MatrixBoundsVisitor::apply(Group& group) {
    if (!needsVisit(group)) return;
    const bool saved = parentChanged_;
    parentChanged_ = parentChanged_ || group.worldStale_ || fullRecompute_;
    group.worldStale_ = false;
    for (const auto& child : group.children())
        if (needsVisit(*child)) child->accept(*this);
    parentChanged_ = saved;
    mergeChildren(group);
}

void MatrixBoundsVisitor::apply(LOD& lod) { apply(static_cast<Group&>(lod)); }

void MatrixBoundsVisitor::apply(Transform& t) {
    if (!needsVisit(t)) return;
    const OpCategory category = t.costCategory();
    OpTally* ops = counter_ ? counter_->tally(category) : nullptr;
    // Without temporal coherence (fullRecompute_) every matrix is rebuilt from its DOFs each frame.
    bool localChanged = t.localDirty_;
    if (t.usesDofs_ && (t.localDirty_ || fullRecompute_)) {
        t.local_ = matrixFromDofs(t.dofs_, ops);
        ++stats_.localMatricesBuilt;
        localChanged = true;
    }
    t.localDirty_ = false;
    const bool changed = localChanged || parentChanged_ || t.worldStale_ || fullRecompute_;
    if (changed) {
        t.world_ = composeAffine(*parentWorld_, t.local_, ops);
        ++stats_.worldMatricesComposed;
        if (counter_) counter_->countOperations(category);
    }
    t.worldStale_ = false;

    const Mat4* savedWorld = parentWorld_;
    const bool savedChanged = parentChanged_;
    parentWorld_ = &t.world_;
    parentChanged_ = changed;
    for (const auto& child : t.children())
        if (needsVisit(*child)) child->accept(*this);
    parentWorld_ = savedWorld;
    parentChanged_ = savedChanged;
    mergeChildren(t);
}

void MatrixBoundsVisitor::apply(Geometry& g) {
    if (!needsVisit(g)) return;
    OpTally* ops = counter_ ? counter_->tally(OpCategory::BsphereRecompute) : nullptr;
    g.worldBound_ = g.drawable().localBound().transformed(*parentWorld_, ops);
    g.boundDirty_ = false;
    g.worldStale_ = false;
    ++stats_.spheresRecomputed;
    if (counter_) counter_->countOperations(OpCategory::BsphereRecompute);
}

}  // namespace throng
