#include "throng/actors/Actor.h"

#include "throng/actors/ActorTraversal.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/TraditionalActorProcessing.h"
#include "throng/scenegraph/AppVisitor.h"
#include "throng/scenegraph/CullVisitor.h"
#include "throng/scenegraph/MatrixBoundsVisitor.h"

namespace throng {

const char ActorTraversal::kKey = 0;

namespace {
ActorTraversal* actorTraversal(const NodeVisitor& v) {
    return static_cast<ActorTraversal*>(v.extension(&ActorTraversal::kKey));
}
}  // namespace

Actor::Actor(Crowd& crowd, ActorId id) : crowd_(&crowd), id_(id) {
    setName("actor" + std::to_string(id));
    setNeedsApp(true);
}

Actor::~Actor() { crowd_->release(this, std::span<const ActorId>(&id_, 1)); }

void Actor::traverseApp(AppVisitor& visitor) {
    if (actorTraversal(visitor)) return;  // actor processing runs phase 1 over the whole crowd itself
    traditionalApp(*crowd_, std::span<const ActorId>(&id_, 1), visitor.context());
    dirtyBound();
}

void Actor::updateMatricesAndBound(MatrixBoundsVisitor& visitor) {
    const std::span<const ActorId> ids(&id_, 1);
    if (ActorTraversal* t = actorTraversal(visitor)) worldBound_ = t->bound(*this, ids, visitor);
    else worldBound_ = traditionalBound(*crowd_, ids, visitor);
}

void Actor::traverseCull(CullVisitor& visitor) {
    const std::span<const ActorId> ids(&id_, 1);
    if (ActorTraversal* t = actorTraversal(visitor)) t->cull(*this, ids, visitor, true);
    else traditionalCull(*crowd_, *this, ids, visitor, false);
}

void Actor::culledOut(CullVisitor& visitor) {
    if (ActorTraversal* t = actorTraversal(visitor)) t->culledOut(*this, std::span<const ActorId>(&id_, 1), visitor);
}

}  // namespace throng
