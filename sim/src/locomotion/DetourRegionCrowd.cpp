// Internal to sim: a region's crowd moved by DetourCrowd (see DetourRegionCrowd.h).

#include "DetourRegionCrowd.h"

#include <DetourCrowd.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace throng::sim::locomotion {

dtCrowd* DetourRegionCrowd::makeCrowd(int capacity) const {
    dtCrowd* crowd = dtAllocCrowd();
    if (!crowd || !crowd->init(capacity, settings_.radius, nav_.detourMesh())) {
        dtFreeCrowd(crowd);
        throw std::runtime_error("Locomotion: DetourCrowd could not be initialised for " + std::to_string(capacity) + " agents");
    }
    // Avoidance quality: the adaptive sampling's divisions, rings and depth, from coarse to Detour's
    // own default (3); Detour's other weights stay as they are.
    static constexpr unsigned char kSampling[4][3] = {{5, 2, 1}, {5, 2, 2}, {7, 2, 3}, {7, 2, 5}};
    const int q = settings_.avoidanceQuality;
    dtObstacleAvoidanceParams params = *crowd->getObstacleAvoidanceParams(q);
    params.adaptiveDivs = kSampling[q][0];
    params.adaptiveRings = kSampling[q][1];
    params.adaptiveDepth = kSampling[q][2];
    crowd->setObstacleAvoidanceParams(q, &params);
    return crowd;
}

DetourRegionCrowd::DetourRegionCrowd(const NavMesh& nav, const Locomotion::Settings& settings, int capacity)
    : nav_(nav), settings_(settings), capacity_(std::min(capacity, kMostAgents)) {
    crowd_ = makeCrowd(capacity_);
}

DetourRegionCrowd::~DetourRegionCrowd() { dtFreeCrowd(crowd_); }

void DetourRegionCrowd::fillParams(const Kept& kept, dtCrowdAgentParams& p) const {
    p = dtCrowdAgentParams{};
    p.radius = settings_.radius;
    p.height = settings_.height;
    p.maxAcceleration = settings_.maxAcceleration;
    p.maxSpeed = kept.maxSpeed;
    p.collisionQueryRange = settings_.radius * settings_.neighbourRange;
    p.pathOptimizationRange = settings_.radius * 30.0f;
    // A ghost only stands in the way: it neither steers nor avoids, and its own move is discarded.
    p.updateFlags = kept.ghost ? 0 : DT_CROWD_ANTICIPATE_TURNS | DT_CROWD_OPTIMIZE_VIS | DT_CROWD_OPTIMIZE_TOPO;
    if (settings_.avoidance && !kept.ghost) p.updateFlags |= DT_CROWD_OBSTACLE_AVOIDANCE | DT_CROWD_SEPARATION;
    p.obstacleAvoidanceType = static_cast<unsigned char>(settings_.avoidanceQuality);
    p.separationWeight = 2.0f;
}

bool DetourRegionCrowd::grow() {
    if (capacity_ >= kMostAgents) return false;
    const int capacity = std::min(2 * capacity_, kMostAgents);
    dtCrowd* bigger = makeCrowd(capacity);
    // Every agent, in order of handle, where it stands, moving as it moved, to where it was going
    // (DetourCrowd plans its path again).
    for (std::size_t h = 0; h < agentOf_.size(); ++h) {
        if (agentOf_[h] < 0) continue;
        const dtCrowdAgent* old = crowd_->getAgent(agentOf_[h]);
        dtCrowdAgentParams p;
        fillParams(kept_[h], p);
        const int agent = bigger->addAgent(old->npos, &p);
        if (agent < 0) {
            dtFreeCrowd(bigger);
            throw std::runtime_error("Locomotion: DetourCrowd could not move an agent into a larger crowd");
        }
        dtCrowdAgent* moved = bigger->getEditableAgent(agent);
        for (int k = 0; k < 3; ++k) moved->vel[k] = moved->dvel[k] = moved->nvel[k] = old->vel[k];
        if (kept_[h].ghost) bigger->requestMoveVelocity(agent, old->vel);
        else if (kept_[h].targetRef) bigger->requestMoveTarget(agent, kept_[h].targetRef, kept_[h].target);
        agentOf_[h] = agent;
    }
    dtFreeCrowd(crowd_);
    crowd_ = bigger;
    capacity_ = capacity;
    return true;
}

int DetourRegionCrowd::add(std::uint32_t, const float* position, const float* velocity, float maxSpeed, bool ghost) {
    Kept kept;
    kept.maxSpeed = maxSpeed;
    kept.ghost = ghost;
    dtCrowdAgentParams p;
    fillParams(kept, p);
    int agent = crowd_->addAgent(position, &p);
    if (agent < 0 && grow()) agent = crowd_->addAgent(position, &p);
    if (agent < 0) return -1;
    if (velocity) {
        dtCrowdAgent* ag = crowd_->getEditableAgent(agent);
        for (int k = 0; k < 3; ++k) ag->vel[k] = ag->dvel[k] = ag->nvel[k] = velocity[k];
        if (ghost) crowd_->requestMoveVelocity(agent, velocity);  // it keeps going as it went
    }
    int handle;
    if (!freeHandles_.empty()) {
        handle = freeHandles_.back();
        freeHandles_.pop_back();
    } else {
        handle = int(agentOf_.size());
        agentOf_.push_back(-1);
        kept_.emplace_back();
    }
    agentOf_[std::size_t(handle)] = agent;
    kept_[std::size_t(handle)] = kept;
    return handle;
}

void DetourRegionCrowd::remove(int handle) {
    crowd_->removeAgent(agentOf_[std::size_t(handle)]);
    agentOf_[std::size_t(handle)] = -1;
    freeHandles_.push_back(handle);
}

void DetourRegionCrowd::requestTarget(int handle, dtPolyRef ref, const float* target) {
    Kept& kept = kept_[std::size_t(handle)];
    kept.targetRef = ref;
    for (int k = 0; k < 3; ++k) kept.target[k] = target[k];
    crowd_->requestMoveTarget(agentOf_[std::size_t(handle)], ref, target);
}

void DetourRegionCrowd::update(float dt) { crowd_->update(dt, nullptr); }

glm::vec3 DetourRegionCrowd::position(int handle) const {
    const float* p = crowd_->getAgent(agentOf_[std::size_t(handle)])->npos;
    return {p[0], p[1], p[2]};
}

glm::vec3 DetourRegionCrowd::velocity(int handle) const {
    const float* v = crowd_->getAgent(agentOf_[std::size_t(handle)])->vel;
    return {v[0], v[1], v[2]};
}

std::size_t DetourRegionCrowd::bytes() const {
    // Every agent slot is allocated up front, each with a 256-polygon path corridor; the proximity
    // grid and the path queue are small beside them.
    return sizeof(dtCrowd) + std::size_t(capacity_) * (sizeof(dtCrowdAgent) + sizeof(dtCrowdAgentAnimation) + 256 * sizeof(dtPolyRef) +
                                                      2 * sizeof(dtCrowdAgent*)) +
           agentOf_.capacity() * sizeof(int) + kept_.capacity() * sizeof(Kept) + freeHandles_.capacity() * sizeof(int);
}

}  // namespace throng::sim::locomotion
