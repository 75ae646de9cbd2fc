#include "throng/vtk/CascadeCuller.h"

#include <stdexcept>
#include <string>

#include <vtkObjectFactory.h>
#include <vtkProp.h>
#include <vtkRenderer.h>

#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/vtk/CameraCascade.h"

namespace throng::vtk {

vtkStandardNewMacro(CascadeCuller)

CascadeCuller::CascadeCuller() = default;
CascadeCuller::~CascadeCuller() = default;

namespace {

// Whether the cascade rejected an actor of class `c` before posing it: with its generic group, by
// CULL 1, by CULL 2 or by occlusion (or it is in no node of the scene).
bool rejectedByCascade(ActorClass c) {
    switch (c) {
        case ActorClass::NotInScene:
        case ActorClass::CulledWithGroup:
        case ActorClass::A:
        case ActorClass::C1:
        case ActorClass::Occluded: return true;
        default: return false;
    }
}

}  // namespace

void CascadeCuller::SetScene(Crowd* crowd, Node* root) {
    cascade_ = std::make_unique<CameraCascade>(crowd, root, "CascadeCuller::SetScene");
    Modified();
}

ActorProcessor* CascadeCuller::GetProcessor() { return cascade_ ? &cascade_->processor() : nullptr; }

void CascadeCuller::SetActorProp(ActorId id, vtkProp* prop) {
    if (!cascade_) throw std::invalid_argument("CascadeCuller::SetActorProp: no scene set (SetScene first)");
    const std::size_t actors = cascade_->crowd().size();
    if (id >= actors)
        throw std::invalid_argument("CascadeCuller::SetActorProp: actor " + std::to_string(id) + " is not in the crowd (" +
                                    std::to_string(actors) + " actors)");
    if (propOf_.size() < actors) propOf_.resize(actors, nullptr);
    if (propOf_[id]) actorOf_.erase(propOf_[id]);  // the actor's previous prop stands for nothing now
    if (prop) {
        const auto previous = actorOf_.find(prop);  // a prop stands for one actor: the last given
        if (previous != actorOf_.end()) propOf_[previous->second] = nullptr;
        actorOf_[prop] = id;
    }
    propOf_[id] = prop;
    Modified();
}

double CascadeCuller::Cull(vtkRenderer* renderer, vtkProp** props, int& count, int& initialized) {
    kept_ = removed_ = 0;
    if (!cascade_ || !renderer || !props) return 0.0;
    last_ = cascade_->run(*renderer);
    const Crowd::State& s = cascade_->crowd().state();
    double total = 0.0;
    int out = 0;
    for (int i = 0; i < count; ++i) {
        vtkProp* prop = props[i];
        const auto actor = actorOf_.find(prop);
        if (actor != actorOf_.end()) {
            if (rejectedByCascade(s.actorClass[actor->second])) {
                ++removed_;
                continue;
            }
            ++kept_;
            if (!initialized) prop->SetRenderTimeMultiplier(1.0);
        } else if (!initialized) {
            prop->SetRenderTimeMultiplier(1.0);
        }
        total += prop->GetRenderTimeMultiplier();
        props[out++] = prop;
    }
    count = out;
    initialized = 1;
    return total;
}

}  // namespace throng::vtk
