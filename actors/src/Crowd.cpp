#include "throng/actors/Crowd.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "throng/actors/Actor.h"
#include "throng/actors/ActorGroup.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/scenegraph/Validation.h"

namespace throng {


Crowd::Crowd() = default;
Crowd::~Crowd() = default;

ActorId Crowd::add(std::shared_ptr<const ActorTemplate> tmpl, std::shared_ptr<Behaviour> behaviour,
                   std::uint32_t slot, const ActorLook& look) {
    if (!tmpl) throw std::invalid_argument("Crowd::add: argument 'tmpl' is null");
    if (!behaviour) throw std::invalid_argument("Crowd::add: argument 'behaviour' is null");
    if (!std::isfinite(look.priority) || !(look.priority > 0.0f))
        throw std::invalid_argument("Crowd::add: argument 'look.priority' must be positive and finite, got " +
                                    std::to_string(look.priority));
    if (!std::isfinite(look.tint.r) || !std::isfinite(look.tint.g) || !std::isfinite(look.tint.b) || !std::isfinite(look.tint.a))
        throw std::invalid_argument("Crowd::add: argument 'look.tint' is not finite");
    const bool clipPoses = behaviour->posesFromTemplateClips();
    const double radius = (clipPoses ? tmpl->skeletonRootRadius() : tmpl->reachRadius()) + behaviour->poseMargin(slot);
    if (!std::isfinite(radius))
        throw std::invalid_argument("Crowd::add: template '" + tmpl->name() +
                                    "' has unbounded DOFs and the behaviour does not play its clips: no Sklsroot "
                                    "Bsphere can be computed");
    const BoundingSphere extent = behaviour->skeletonRootExtent(slot);

    State& s = state_;
    const auto id = static_cast<ActorId>(s.tmpl.size());
    s.tmpl.push_back(tmpl.get());
    s.behaviour.push_back(behaviour.get());
    s.slot.push_back(slot);
    s.refSphereLocal.emplace_back(extent.center(), extent.radius() + radius);
    for (PagedArray<Mat4>* matrices : {&s.refLocal, &s.refWorld, &s.sklsWorld}) matrices->appendUnwritten(1);
    s.refSphereWorld.appendUnwritten(1);
    s.root.appendUnwritten(1);
    s.dofs.appendUnwritten(tmpl->dofValueCount());
    s.stateWritten.push_back(0);
    ++deferred_;
    s.sklsRadius.push_back(radius);
    s.eyeDistance.push_back(std::numeric_limits<double>::infinity());
    s.priority.push_back(look.priority);
    s.tint.push_back(look.tint);
    s.body.push_back(look.body);
    s.dofOffset.push_back(static_cast<std::uint32_t>(s.dofs.size() - tmpl->dofValueCount()));
    s.nodeOffset.push_back(s.totalNodes);
    s.totalNodes += static_cast<std::uint32_t>(tmpl->nodeCount());
    s.owner.push_back(nullptr);
    s.member.push_back(0);
    s.held.push_back(-1);
    s.actorClass.push_back(ActorClass::NotInScene);
    s.present.push_back(1);
    if (!deferring_) writeInitialState(id);

    if (std::find(templates_.begin(), templates_.end(), tmpl) == templates_.end()) templates_.push_back(std::move(tmpl));
    auto known = std::find(behaviours_.begin(), behaviours_.end(), behaviour);
    if (known == behaviours_.end()) {
        behaviours_.push_back(std::move(behaviour));
        actorsBySlot_.emplace_back();
        known = behaviours_.end() - 1;
    }
    std::vector<ActorId>& bySlot = actorsBySlot_[std::size_t(known - behaviours_.begin())];
    if (bySlot.size() <= slot) bySlot.resize(std::size_t(slot) + 1, kNoActor);
    bySlot[slot] = id;
    return id;
}

void Crowd::claim(ActorId id, Node* owner, std::uint32_t member, const char* who) {
    if (id >= size())
        throw std::invalid_argument(std::string(who) + ": actor " + std::to_string(id) + " does not exist (" +
                                    std::to_string(size()) + " actors)");
    if (state_.owner[id])
        throw std::invalid_argument(std::string(who) + ": actor " + std::to_string(id) + " already belongs to node '" +
                                    state_.owner[id]->name() + "'");
    state_.owner[id] = owner;
    state_.member[id] = member;
    inScene_ += owner != nullptr;
}

std::shared_ptr<Actor> Crowd::makeActorNode(ActorId id) {
    if (id >= size() || state_.owner[id]) claim(id, nullptr, 0, "Crowd::makeActorNode");  // throws
    auto node = std::make_shared<Actor>(*this, id);
    claim(id, node.get(), 0, "Crowd::makeActorNode");
    nodeSlot_[node.get()] = nodes_.size();
    nodes_.push_back(node.get());
    return node;
}

std::shared_ptr<ActorGroup> Crowd::makeGroupNode(std::vector<ActorId> ids) {
    std::vector<ActorId> sorted = ids;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
        throw std::invalid_argument("Crowd::makeGroupNode: an actor is listed twice");
    for (ActorId id : ids)
        if (id >= size() || state_.owner[id]) claim(id, nullptr, 0, "Crowd::makeGroupNode");  // throws
    auto node = std::make_shared<ActorGroup>(*this, std::move(ids));
    std::uint32_t member = 0;
    for (ActorId id : node->ids()) claim(id, node.get(), member++, "Crowd::makeGroupNode");
    nodeSlot_[node.get()] = nodes_.size();
    nodes_.push_back(node.get());
    return node;
}

void Crowd::hold(ActorId id, HeldObject object) {
    if (id >= size()) throw std::invalid_argument("Crowd::hold: actor " + std::to_string(id) + " does not exist");
    const ActorTemplate& t = *state_.tmpl[id];
    if (object.node < 0 || static_cast<std::size_t>(object.node) >= t.nodeCount())
        throw std::invalid_argument("Crowd::hold: template '" + t.name() + "' has no node " + std::to_string(object.node));
    if (!object.drawable) throw std::invalid_argument("Crowd::hold: argument 'object.drawable' is null");
    const bool sampled = state_.behaviour[id]->posesFromTemplateClips();
    const auto node = static_cast<std::size_t>(object.node);
    const BoundingSphere& b = object.drawable->localBound();
    const double reach = t.nodeReach(node, sampled) + t.nodeScale(node, sampled) * (glm::length(b.center()) + b.radius());
    if (!std::isfinite(reach))
        throw std::invalid_argument("Crowd::hold: node '" + t.nodes()[node].name + "' of template '" + t.name() +
                                    "' has no bounded reach, so the held object cannot be enclosed");
    if (state_.held[id] < 0) {
        state_.held[id] = static_cast<std::int32_t>(state_.heldObjects.size());
        state_.heldObjects.emplace_back();
    }
    state_.heldObjects[static_cast<std::size_t>(state_.held[id])].push_back(std::move(object));
    // Both static spheres grow coherently (seed 002 §4.3).
    if (reach > state_.sklsRadius[id]) {
        const double grow = reach - state_.sklsRadius[id];
        state_.sklsRadius[id] = reach;
        state_.refSphereLocal[id].inflate(grow);
    }
    if (state_.owner[id]) state_.owner[id]->dirtyBound();
}

void Crowd::setPriority(ActorId id, float priority) {
    if (id >= size()) throw std::invalid_argument("Crowd::setPriority: actor " + std::to_string(id) + " does not exist");
    if (!std::isfinite(priority) || !(priority > 0.0f))
        throw std::invalid_argument("Crowd::setPriority: argument 'priority' must be positive and finite");
    state_.priority[id] = priority;
}

std::span<const float> Crowd::dofs(ActorId id) const {
    if (!state_.stateWritten[id]) return state_.tmpl[id]->restDofs();
    return std::span<const float>(state_.dofs).subspan(state_.dofOffset[id], state_.tmpl[id]->dofValueCount());
}

void Crowd::writeInitialState(ActorId id) {
    State& s = state_;
    s.refLocal[id] = s.refWorld[id] = s.sklsWorld[id] = Mat4(1.0);
    s.refSphereWorld[id] = BoundingSphere();
    s.root[id] = RootPose();
    const std::span<const float> rest = s.tmpl[id]->restDofs();
    std::copy(rest.begin(), rest.end(), s.dofs.data() + s.dofOffset[id]);
    s.stateWritten[id] = 1;
    --deferred_;
}

void Crowd::writeAllStates() {
    if (deferred_ == 0) return;
    for (ActorId id = 0; id < size(); ++id) writeState(id);
}

std::size_t Crowd::bytesPerActor(const ActorTemplate& tmpl) const {
    std::size_t bytes = sizeof(const ActorTemplate*) + sizeof(Behaviour*) + sizeof(std::uint32_t) + 3 * sizeof(Mat4) +
                        2 * sizeof(BoundingSphere) + sizeof(RootPose) + 2 * sizeof(double) + sizeof(float) +
                        sizeof(glm::vec4) + 2 * sizeof(std::uint32_t) + sizeof(Node*) + sizeof(std::uint32_t) +
                        sizeof(std::int32_t) + sizeof(ActorClass) + 2 * sizeof(std::uint8_t) + tmpl.dofValueCount() * sizeof(float);
    // The behaviour's slot, counted with the first behaviour seen (they are similar in size).
    if (!state_.behaviour.empty()) bytes += state_.behaviour.front()->bytesPerSlot();
    return bytes;
}

Crowd::TraditionalWorkspace& Crowd::traditionalWorkspace() {
    TraditionalWorkspace& w = traditional_;
    if (w.model.size() != state_.totalNodes || w.whole.size() != size()) {
        w.model.resize(state_.totalNodes);
        w.world.resize(state_.totalNodes);
        w.geometry.resize(state_.totalNodes);
        w.subtree.resize(state_.totalNodes);
        w.whole.resize(size());
    }
    return w;
}

void Crowd::release(Node* node, std::span<const ActorId> ids) {
    for (ActorId id : ids)
        if (id < size() && state_.owner[id] == node) state_.owner[id] = nullptr, --inScene_;
    // The last node takes the released one's place: a scene torn down node by node stays linear
    // (erasing from the front took 2.2 s for 100,000 nodes).
    const auto slot = nodeSlot_.find(node);
    if (slot == nodeSlot_.end()) return;
    const std::size_t at = slot->second;
    nodeSlot_.erase(slot);
    if (at + 1 != nodes_.size()) {
        nodes_[at] = nodes_.back();
        nodeSlot_[nodes_[at]] = at;
    }
    nodes_.pop_back();
}

void Crowd::step(const FrameContext& context) {
    requireFinite(context.time, "Crowd::step", "context.time");
    requireFinite(context.deltaTime, "Crowd::step", "context.deltaTime");
    if (steps_ > 0 && context.time < time_)
        throw std::invalid_argument("Crowd::step: time " + std::to_string(context.time) + " s is before the last step's " +
                                    std::to_string(time_) + " s");
    Stopwatch watch;
    for (const auto& b : behaviours_) b->advance(context);
    lastStepMs_ = watch.elapsedMs();
    time_ = context.time;
    ++steps_;
}

}  // namespace throng
