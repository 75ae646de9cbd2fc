// Internal to sim: Locomotion's regions, each stepped by its own crowd (see RegionStepper.h).

#include "RegionStepper.h"

#include <DetourNavMeshQuery.h>

#include "DetourRegionCrowd.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/CounterRng.h"

namespace throng::sim::locomotion {

RegionStepper::RegionStepper(const NavMesh& nav, const Locomotion::Settings& settings, std::span<const Locomotion::Actor> actors,
                             std::span<WalkerState> walkers, std::span<std::uint32_t> regionOf)
    : nav_(nav), settings_(settings), actors_(actors), state_(walkers), regionOf_(regionOf) {}

RegionStepper::~RegionStepper() {
    for (Region& r : regions_) {
        r.crowd.reset();
        dtFreeNavMeshQuery(r.query);
    }
}

dtPolyRef RegionStepper::nearestOnMesh(Region& region, const glm::vec3& p, const glm::vec3& extents, glm::vec3& snapped) {
    dtQueryFilter filter;
    dtPolyRef ref = 0;
    region.query->findNearestPoly(&p.x, &extents.x, &filter, &ref, &snapped.x);
    return ref;
}

void RegionStepper::requestTarget(Region& region, std::uint32_t slot) {
    WalkerState& s = state_[slot];
    glm::vec3 snapped;
    if (const dtPolyRef ref = nearestOnMesh(region, s.target, glm::vec3(2.0f, 4.0f, 2.0f), snapped))
        region.crowd->requestTarget(s.agent, ref, &snapped.x);
}

void RegionStepper::newDestination(Region& region, std::uint32_t slot) {
    WalkerState& s = state_[slot];
    const Locomotion::Actor& a = actors_[slot];
    if (a.goal && s.trips > 0) return;  // there, or on its way: a fixed goal is asked for once
    const CounterRng rng(settings_.seed, a.stream);
    bool found = false;
    if (!a.goal && settings_.destinationRange > 0.0) {
        // A few tries at a point within range that lies on the mesh; then anywhere.
        for (std::uint64_t k = 0; k < 8 && !found; ++k) {
            const std::uint64_t c = (s.trips * 8 + k) * 2 + (std::uint64_t(1) << 40);  // apart from randomPoint's counters
            const glm::vec3 want = s.position + glm::vec3(float(rng.uniform(c, -1.0, 1.0) * settings_.destinationRange), 0.0f,
                                                          float(rng.uniform(c + 1, -1.0, 1.0) * settings_.destinationRange));
            glm::vec3 snapped;
            if (nearestOnMesh(region, want, glm::vec3(2.0f, 4.0f, 2.0f), snapped)) s.target = snapped, found = true;
        }
    }
    if (!found) s.target = a.goal ? *a.goal : nav_.randomPoint(rng, s.trips, *region.query);
    ++s.trips;
    requestTarget(region, slot);
}

int RegionStepper::addAgent(Region& region, std::uint32_t r, std::uint32_t slot, const float* position, const float* velocity,
                            bool ghost) {
    const int agent = region.crowd->add(slot, position, velocity, static_cast<float>(actors_[slot].speed), ghost);
    if (agent < 0)
        throw std::runtime_error("Locomotion: region " + std::to_string(r) + " is full (" + std::to_string(DetourRegionCrowd::kMostAgents) +
                                 " agents with its ghosts, DetourCrowd's most); declare smaller regions");
    return agent;
}

void RegionStepper::startRegion(std::uint32_t r) {
    Region& region = regions_[r];
    region.query = nav_.newQuery();
    if (settings_.avoidanceModel == Locomotion::AvoidanceModel::Orca)
        region.crowd = std::make_unique<OrcaRegionCrowd>(settings_, *region.query, orcaWorkers_);
    else
        region.crowd = std::make_unique<DetourRegionCrowd>(nav_, settings_, region.capacity);
    for (std::uint32_t slot : region.owned) {
        state_[slot].agent = addAgent(region, r, slot, &state_[slot].position.x, nullptr, false);
        newDestination(region, slot);
    }
}

void RegionStepper::place() {
    const RegionGrid& grid = settings_.regions;
    if (grid.regionCount() > 1 && double(settings_.radius) * double(settings_.neighbourRange) >= grid.cellSize())
        throw std::invalid_argument("Locomotion: region cells of " + std::to_string(grid.cellSize()) +
                                    " m are narrower than the agents' collision range");
    regions_.resize(grid.regionCount());
    regionBounds_ = grid.regionBounds();
    pending_.assign(regions_.size(), 0.0);
    stepping_.assign(regions_.size(), 1);
    for (std::uint32_t slot = 0; slot < state_.size(); ++slot) {
        const WalkerState& s = state_[slot];
        regionOf_[slot] = grid.regionOf(s.position.x, s.position.z);
        regions_[regionOf_[slot]].owned.push_back(slot);
    }
    // Room for the agents a region starts with (or its share of the crowd) and a quarter more, and
    // its ghosts; a DetourCrowd grows when people gather (an ORCA crowd grows as it goes); DetourCrowd
    // numbers agents with 16 bits.
    const std::size_t share = state_.size() / regions_.size();
    for (std::uint32_t r = 0; r < regions_.size(); ++r) {
        const std::size_t most = std::max(regions_[r].owned.size(), share);
        const std::size_t want = most + most / 4 + 64;
        if (regions_[r].owned.size() > 40000)
            throw std::runtime_error("Locomotion: region " + std::to_string(r) + " starts with " + std::to_string(regions_[r].owned.size()) +
                                     " agents; DetourCrowd numbers a crowd's agents with 16 bits, so declare smaller regions");
        regions_[r].capacity = int(std::min<std::size_t>(want, 65000));
    }
}

void RegionStepper::start(std::uint32_t first, std::uint32_t end) {
    forEachChunk(end - first, 1, [&](std::size_t, std::size_t begin, std::size_t stop) {
        for (std::size_t r = begin; r < stop; ++r) startRegion(first + std::uint32_t(r));
    });
}

void RegionStepper::prepareStep() {
    if (settings_.avoidanceModel == Locomotion::AvoidanceModel::Orca) orcaWorkers_.prepare(nav_);
}

std::size_t RegionStepper::bytes() const {
    std::size_t b = orcaWorkers_.bytes() + regions_.capacity() * sizeof(Region);
    for (const Region& r : regions_) {
        if (r.crowd) b += r.crowd->bytes();
        b += (r.owned.capacity() + r.scratch.capacity()) * sizeof(std::uint32_t) + r.ghostAgents.capacity() * sizeof(int);
        b += (r.ghostsOut.capacity() + r.ghostsIn.capacity()) * sizeof(GhostRecord);
        b += (r.leaving.capacity() + r.arriving.capacity()) * sizeof(HandoverRecord);
    }
    return b;
}

std::size_t RegionStepper::chooseStepping(std::uint32_t first, std::uint32_t end, double dt, glm::vec3 viewpoint) {
    ++steps_;
    std::size_t deferred = 0;
    const double farSquared = settings_.farDistance * settings_.farDistance;
    for (std::uint32_t r = first; r < end; ++r) {
        pending_[r] += dt;
        bool now = true;
        if (settings_.farEvery > 1 && regions_.size() > 1) {
            const glm::dvec4& b = regionBounds_[r];
            const double dx = std::max({0.0, b.x - viewpoint.x, viewpoint.x - b.z});
            const double dz = std::max({0.0, b.y - viewpoint.z, viewpoint.z - b.w});
            now = dx * dx + dz * dz <= farSquared || (steps_ + r) % std::uint64_t(settings_.farEvery) == 0;
        }
        stepping_[r] = now;
        if (!now) deferred += regions_[r].owned.size();
    }
    return deferred;
}

void RegionStepper::exportGhosts(std::uint32_t r) {
    Region& region = regions_[r];
    region.ghostsOut.clear();
    if (regions_.size() == 1) return;
    const double margin = double(settings_.radius) * double(settings_.neighbourRange);  // the collision query range
    std::uint32_t near[8];
    for (std::uint32_t slot : region.owned) {
        const WalkerState& s = state_[slot];
        const int n = settings_.regions.regionsNear(s.position.x, s.position.z, margin, r, near);
        for (int k = 0; k < n; ++k) {
            GhostRecord g;
            g.slot = slot;
            g.region = near[k];
            for (int i = 0; i < 3; ++i) g.position[i] = s.position[i], g.velocity[i] = s.velocity[i];
            region.ghostsOut.push_back(g);
        }
    }
}

std::size_t RegionStepper::deliverGhosts() {
    std::size_t delivered = 0;
    for (Region& region : regions_) region.ghostsIn.clear();
    for (Region& region : regions_)
        for (const GhostRecord& g : region.ghostsOut) regions_[g.region].ghostsIn.push_back(g), ++delivered;
    return delivered;
}

void RegionStepper::importGhosts(std::uint32_t r) {
    Region& region = regions_[r];
    region.ghostAgents.clear();
    for (const GhostRecord& g : region.ghostsIn) region.ghostAgents.push_back(addAgent(region, r, g.slot, g.position, g.velocity, true));
}

void RegionStepper::stepRegion(std::uint32_t r, float dt) {
    Region& region = regions_[r];
    if (!stepping_[r]) {  // a far region waiting for its turn: its walkers carry on as they went
        for (std::uint32_t slot : region.owned) state_[slot].position += state_[slot].velocity * dt;
        return;
    }
    dt = static_cast<float>(pending_[r]);  // the time since it last stepped
    pending_[r] = 0.0;
    for (std::uint32_t slot : region.owned) {
        const WalkerState& s = state_[slot];
        const glm::vec3 d = s.target - s.position;
        if (d.x * d.x + d.z * d.z < 1.0f) newDestination(region, slot);
    }
    importGhosts(r);
    region.crowd->update(dt);
    for (int agent : region.ghostAgents) region.crowd->remove(agent);
    for (std::uint32_t slot : region.owned) {
        WalkerState& s = state_[slot];
        s.position = region.crowd->position(s.agent);
        s.velocity = region.crowd->velocity(s.agent);
        wrapAround(region, r, slot);
    }
}

void RegionStepper::wrapAround(Region& region, std::uint32_t r, std::uint32_t slot) {
    const Locomotion::Actor& a = actors_[slot];
    if (!a.goal || (a.period.x == 0.0f && a.period.z == 0.0f)) return;  // most walkers: no goal, or not periodic
    const float period = glm::length(a.period);
    WalkerState& s = state_[slot];
    if (glm::dot(s.position - s.target, a.period) / period < -1.0f) return;  // not yet within 1 m of the goal's line
    const glm::vec3 back = s.position - a.period;
    region.crowd->remove(s.agent);
    // The region's own query: regions step in parallel, and the mesh's shared one is not thread-safe.
    if (!nearestOnMesh(region, back, glm::vec3(1.0f, 2.0f, 1.0f), s.position)) s.position = back;
    s.agent = addAgent(region, r, slot, &s.position.x, &s.velocity.x, false);
    requestTarget(region, slot);
}

void RegionStepper::exportHandovers(std::uint32_t r) {
    Region& region = regions_[r];
    region.leaving.clear();
    if (regions_.size() == 1) return;
    for (std::uint32_t slot : region.owned) {
        const WalkerState& s = state_[slot];
        const std::uint32_t to = settings_.regions.regionOf(s.position.x, s.position.z);
        if (to == r) continue;
        HandoverRecord h;
        h.slot = slot;
        h.from = r;
        h.to = to;
        for (int i = 0; i < 3; ++i) h.position[i] = s.position[i], h.velocity[i] = s.velocity[i], h.target[i] = s.target[i];
        h.heading = s.heading, h.speed = s.speed, h.runWeight = s.runWeight, h.phase = s.phase, h.trips = s.trips;
        h.carried = s.carried;
        region.leaving.push_back(h);
        region.crowd->remove(s.agent);
    }
}

std::size_t RegionStepper::deliverHandovers() {
    std::size_t delivered = 0;
    for (Region& region : regions_) region.arriving.clear();
    for (Region& region : regions_)
        for (const HandoverRecord& h : region.leaving) regions_[h.to].arriving.push_back(h), ++delivered;
    return delivered;
}

void RegionStepper::importHandovers(std::uint32_t r) {
    Region& region = regions_[r];
    if (region.leaving.empty() && region.arriving.empty()) return;
    // Arrivals join in order of slot, whichever region they come from.
    std::sort(region.arriving.begin(), region.arriving.end(), [](const HandoverRecord& a, const HandoverRecord& b) { return a.slot < b.slot; });
    for (const HandoverRecord& h : region.arriving) {
        WalkerState& s = state_[h.slot];  // as the record has it: it may come from another rank
        regionOf_[h.slot] = r;
        s.position = glm::vec3(h.position[0], h.position[1], h.position[2]);
        s.velocity = glm::vec3(h.velocity[0], h.velocity[1], h.velocity[2]);
        s.target = glm::vec3(h.target[0], h.target[1], h.target[2]);
        s.heading = h.heading, s.speed = h.speed, s.runWeight = h.runWeight, s.phase = h.phase, s.trips = h.trips;
        s.carried = std::uint8_t(h.carried);
        s.agent = addAgent(region, r, h.slot, h.position, h.velocity, false);
        requestTarget(region, h.slot);
    }
    // The slots it owns, still increasing: those that stayed merged with those that came.
    region.scratch.clear();
    std::size_t k = 0, gone = 0;
    for (std::uint32_t slot : region.owned) {
        if (gone < region.leaving.size() && region.leaving[gone].slot == slot) {  // left (listed in the same order)
            ++gone;
            continue;
        }
        while (k < region.arriving.size() && region.arriving[k].slot < slot) region.scratch.push_back(region.arriving[k++].slot);
        region.scratch.push_back(slot);
    }
    for (; k < region.arriving.size(); ++k) region.scratch.push_back(region.arriving[k].slot);
    region.owned.swap(region.scratch);
}

}  // namespace throng::sim::locomotion
