// Internal to sim: a region's crowd moved by DetourCrowd (see DetourRegionCrowd.h).

#include "DetourRegionCrowd.h"

#include <DetourCrowd.h>

#include <stdexcept>
#include <string>

namespace throng::sim::locomotion {

DetourRegionCrowd::DetourRegionCrowd(const NavMesh& nav, const Locomotion::Settings& settings, int capacity)
    : settings_(settings), crowd_(dtAllocCrowd()), capacity_(capacity) {
    if (!crowd_ || !crowd_->init(capacity, settings.radius, nav.detourMesh())) {
        dtFreeCrowd(crowd_);
        throw std::runtime_error("Locomotion: DetourCrowd could not be initialised for " + std::to_string(capacity) + " agents");
    }
    // Avoidance quality: the adaptive sampling's divisions, rings and depth, from coarse to Detour's
    // own default (3); Detour's other weights stay as they are.
    static constexpr unsigned char kSampling[4][3] = {{5, 2, 1}, {5, 2, 2}, {7, 2, 3}, {7, 2, 5}};
    const int q = settings.avoidanceQuality;
    dtObstacleAvoidanceParams params = *crowd_->getObstacleAvoidanceParams(q);
    params.adaptiveDivs = kSampling[q][0];
    params.adaptiveRings = kSampling[q][1];
    params.adaptiveDepth = kSampling[q][2];
    crowd_->setObstacleAvoidanceParams(q, &params);
}

DetourRegionCrowd::~DetourRegionCrowd() { dtFreeCrowd(crowd_); }

int DetourRegionCrowd::add(std::uint32_t, const float* position, const float* velocity, float maxSpeed, bool ghost) {
    dtCrowdAgentParams p{};
    p.radius = settings_.radius;
    p.height = settings_.height;
    p.maxAcceleration = settings_.maxAcceleration;
    p.maxSpeed = maxSpeed;
    p.collisionQueryRange = settings_.radius * settings_.neighbourRange;
    p.pathOptimizationRange = settings_.radius * 30.0f;
    // A ghost only stands in the way: it neither steers nor avoids, and its own move is discarded.
    p.updateFlags = ghost ? 0 : DT_CROWD_ANTICIPATE_TURNS | DT_CROWD_OPTIMIZE_VIS | DT_CROWD_OPTIMIZE_TOPO;
    if (settings_.avoidance && !ghost) p.updateFlags |= DT_CROWD_OBSTACLE_AVOIDANCE | DT_CROWD_SEPARATION;
    p.obstacleAvoidanceType = static_cast<unsigned char>(settings_.avoidanceQuality);
    p.separationWeight = 2.0f;
    const int agent = crowd_->addAgent(position, &p);
    if (agent < 0 || !velocity) return agent;
    dtCrowdAgent* ag = crowd_->getEditableAgent(agent);
    for (int k = 0; k < 3; ++k) ag->vel[k] = ag->dvel[k] = ag->nvel[k] = velocity[k];
    if (ghost) crowd_->requestMoveVelocity(agent, velocity);  // it keeps going as it went
    return agent;
}

void DetourRegionCrowd::remove(int agent) { crowd_->removeAgent(agent); }

void DetourRegionCrowd::requestTarget(int agent, dtPolyRef ref, const float* target) { crowd_->requestMoveTarget(agent, ref, target); }

void DetourRegionCrowd::update(float dt) { crowd_->update(dt, nullptr); }

glm::vec3 DetourRegionCrowd::position(int agent) const {
    const float* p = crowd_->getAgent(agent)->npos;
    return {p[0], p[1], p[2]};
}

glm::vec3 DetourRegionCrowd::velocity(int agent) const {
    const float* v = crowd_->getAgent(agent)->vel;
    return {v[0], v[1], v[2]};
}

std::size_t DetourRegionCrowd::bytes() const {
    // Every agent slot is allocated up front, each with a 256-polygon path corridor; the proximity
    // grid and the path queue are small beside them.
    return sizeof(dtCrowd) + std::size_t(capacity_) * (sizeof(dtCrowdAgent) + sizeof(dtCrowdAgentAnimation) + 256 * sizeof(dtPolyRef) +
                                                      2 * sizeof(dtCrowdAgent*));
}

}  // namespace throng::sim::locomotion
