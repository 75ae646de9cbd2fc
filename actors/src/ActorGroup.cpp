#include "throng/actors/ActorGroup.h"

#include "throng/actors/ActorTraversal.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/TraditionalActorProcessing.h"
#include "throng/scenegraph/AppVisitor.h"
#include "throng/scenegraph/CullVisitor.h"
#include "throng/scenegraph/MatrixBoundsVisitor.h"

namespace throng {
namespace {
ActorTraversal* actorTraversal(const NodeVisitor& v) {
    return static_cast<ActorTraversal*>(v.extension(&ActorTraversal::kKey));
}
}  // namespace

ActorGroup::ActorGroup(Crowd& crowd, std::vector<ActorId> ids) : crowd_(&crowd), ids_(std::move(ids)) {
    setName("actorGroup");
    setNeedsApp(true);
}

ActorGroup::~ActorGroup() { crowd_->release(this, ids_); }

void ActorGroup::traverseApp(AppVisitor& visitor) {
    if (actorTraversal(visitor)) return;  // actor processing runs phase 1 over the whole crowd itself
    traditionalApp(*crowd_, ids_, visitor.context());
    dirtyBound();
}

void ActorGroup::updateMatricesAndBound(MatrixBoundsVisitor& visitor) {
    if (ActorTraversal* t = actorTraversal(visitor)) worldBound_ = t->bound(*this, ids_, visitor, roamingBound_);
    else worldBound_ = traditionalBound(*crowd_, ids_, visitor);
}

void ActorGroup::traverseCull(CullVisitor& visitor) {
    if (ActorTraversal* t = actorTraversal(visitor)) t->cull(*this, ids_, visitor, ids_.size() == 1 && !roamingBound_.valid());
    else traditionalCull(*crowd_, *this, ids_, visitor, true);
}

void ActorGroup::culledOut(CullVisitor& visitor) {
    if (ActorTraversal* t = actorTraversal(visitor)) t->culledOut(*this, ids_, visitor);
}

}  // namespace throng
