// Internal to sim: a region's crowd kept apart by ORCA along Detour path corridors (see
// OrcaRegionCrowd.h).

#include "OrcaRegionCrowd.h"

#include <DetourLocalBoundary.h>
#include <DetourNavMeshQuery.h>
#include <DetourPathCorridor.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "throng/scenegraph/ThreadTeam.h"

namespace throng::sim::locomotion {
namespace {

const dtQueryFilter kFilter;

// Walkers per chunk of the parallel loops.
constexpr std::size_t kGrain = 64;
// Node pool of a worker's query (the mesh's own queries have 4096): a search that runs out of nodes
// returns the part it found, walked and then planned on from near its end.
constexpr int kWorkerNodes = 1024;

glm::vec2 ground(const glm::vec3& v) { return {v.x, v.z}; }

// The share of its free speed a walker keeps at `density` persons/m^2: Weidmann's (1993) fundamental
// diagram, v(rho) = v0 (1 - exp(-1.913 (1/rho - 1/5.4))), scaled to the walker's own free speed.
float weidmannShare(float density) {
    if (density <= 1e-3f) return 1.0f;
    return std::max(0.0f, 1.0f - std::exp(-1.913f * (1.0f / density - 1.0f / 5.4f)));
}

}  // namespace

OrcaWorkers::~OrcaWorkers() {
    for (Worker& w : workers_) dtFreeNavMeshQuery(w.query);
}

void OrcaWorkers::prepare(const NavMesh& nav) {
    const std::size_t want = workerSlots();
    while (workers_.size() < want) {
        Worker w;
        w.query = dtAllocNavMeshQuery();
        if (!w.query || dtStatusFailed(w.query->init(nav.detourMesh(), kWorkerNodes))) {
            dtFreeNavMeshQuery(w.query);
            throw std::runtime_error("Locomotion: Detour could not initialise a navigation query for ORCA's threads");
        }
        w.path.resize(OrcaRegionCrowd::kMaxPath);
        w.lines.resize(8 + OrcaRegionCrowd::kMaxNeighbours);  // a local boundary holds at most 8 walls
        w.scratch.resize(w.lines.size());
        workers_.push_back(std::move(w));
    }
}

OrcaWorkers::Worker& OrcaWorkers::mine() {
    const std::size_t index = workerIndex();
    if (index >= workers_.size()) throw std::logic_error("Locomotion: a thread ORCA's workers were not prepared for");
    return workers_[index];
}

std::size_t OrcaWorkers::bytes() const {
    std::size_t b = workers_.capacity() * sizeof(Worker);
    for (const Worker& w : workers_)
        b += sizeof(dtNavMeshQuery) + std::size_t(kWorkerNodes) * 48 + w.path.capacity() * sizeof(dtPolyRef) +
             (w.lines.capacity() + w.scratch.capacity()) * sizeof(orca::Line);  // 48: a node and its hash entry
    return b;
}

OrcaRegionCrowd::OrcaRegionCrowd(const Locomotion::Settings& settings, dtNavMeshQuery& query, OrcaWorkers& workers)
    : settings_(settings), query_(query), workers_(workers) {
}

OrcaRegionCrowd::~OrcaRegionCrowd() = default;

int OrcaRegionCrowd::add(std::uint32_t slot, const float* position, const float* velocity, float maxSpeed, bool ghost) {
    int agent;
    if (!free_.empty()) {
        agent = free_.back();
        free_.pop_back();
    } else {
        agent = int(position_.size());
        position_.emplace_back(), velocity_.emplace_back(), target_.emplace_back(), next_.emplace_back(), way_.emplace_back(), nextWay_.emplace_back();
        planned_.emplace_back(), corrected_.emplace_back(), neighbourCount_.push_back(0), corners_.emplace_back(), turn_.emplace_back();
        neighbours_.resize(neighbours_.size() + kMaxNeighbours);
        maxSpeed_.push_back(0.0f), slot_.push_back(0), kind_.push_back(kFree), needsPath_.push_back(0), targetRef_.push_back(0);
        corridor_.emplace_back(), boundary_.emplace_back();
    }
    const std::size_t i = std::size_t(agent);
    position_[i] = glm::vec3(position[0], position[1], position[2]);
    velocity_[i] = velocity ? glm::vec3(velocity[0], 0.0f, velocity[2]) : glm::vec3(0.0f);
    next_[i] = ground(velocity_[i]);
    way_[i] = nextWay_[i] = glm::vec2(0.0f);
    target_[i] = position_[i];
    maxSpeed_[i] = maxSpeed;
    slot_[i] = slot;
    kind_[i] = ghost ? kGhost : kWalker;
    needsPath_[i] = 0;
    targetRef_[i] = 0;
    neighbourCount_[i] = 0;
    corners_[i].count = -1;
    // A small turn of its way, fixed per walker, so that two walkers meeting exactly head-on do not
    // stall (ORCA's half-planes are symmetric): within a degree either way.
    const float angle = (float((slot * 2654435761u) >> 16 & 0xffffu) / 65535.0f * 2.0f - 1.0f) * 0.01745f;
    turn_[i] = glm::vec2(std::cos(angle), std::sin(angle));
    if (ghost) return agent;
    if (!corridor_[i]) {
        corridor_[i] = std::make_unique<dtPathCorridor>();
        boundary_[i] = std::make_unique<dtLocalBoundary>();
        if (!corridor_[i]->init(kMaxPath)) throw std::runtime_error("Locomotion: Detour could not allocate a path corridor");
    }
    // Onto the mesh, as DetourCrowd places its agents; one nowhere near it stands where it is.
    const float r = settings_.radius;
    const float extents[3] = {2.0f * r, 1.5f * r, 2.0f * r};
    dtPolyRef ref = 0;
    float nearest[3];
    query_.findNearestPoly(position, extents, &kFilter, &ref, nearest);
    if (ref) position_[i] = glm::vec3(nearest[0], nearest[1], nearest[2]);
    corridor_[i]->reset(ref, &position_[i].x);
    boundary_[i]->reset();
    return agent;
}

void OrcaRegionCrowd::remove(int agent) {
    kind_[std::size_t(agent)] = kFree;
    free_.push_back(agent);
}

void OrcaRegionCrowd::requestTarget(int agent, dtPolyRef ref, const float* target) {
    const std::size_t i = std::size_t(agent);
    targetRef_[i] = ref;
    target_[i] = glm::vec3(target[0], target[1], target[2]);
    needsPath_[i] = 1;
}

std::int32_t OrcaRegionCrowd::column(float x) const {
    return std::clamp(std::int32_t(std::floor((x - gridOrigin_.x) / cellSize_)), 0, columns_ - 1);
}

std::int32_t OrcaRegionCrowd::row(float z) const {
    return std::clamp(std::int32_t(std::floor((z - gridOrigin_.y) / cellSize_)), 0, rows_ - 1);
}

void OrcaRegionCrowd::buildGrid() {
    // Cells half the neighbour range wide over the agents' bounds; wider when that would make many
    // more cells than agents (a few walkers spread over a large region).
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (std::uint32_t i : agents_) lo = glm::min(lo, ground(position_[i])), hi = glm::max(hi, ground(position_[i]));
    if (agents_.empty()) lo = hi = glm::vec2(0.0f);
    cellSize_ = std::max(0.25f, 0.5f * settings_.radius * settings_.neighbourRange);
    const double most = std::max<double>(4096.0, 4.0 * double(agents_.size()));
    while (double((hi.x - lo.x) / cellSize_ + 1.0f) * double((hi.y - lo.y) / cellSize_ + 1.0f) > most) cellSize_ *= 2.0f;
    gridOrigin_ = lo;
    columns_ = std::int32_t((hi.x - lo.x) / cellSize_) + 1;
    rows_ = std::int32_t((hi.y - lo.y) / cellSize_) + 1;
    const std::size_t cells = std::size_t(columns_) * std::size_t(rows_);
    cellStart_.assign(cells + 1, 0);
    agentCell_.resize(position_.size());
    for (std::uint32_t i : agents_) {
        const std::uint32_t c = std::uint32_t(row(position_[i].z) * columns_ + column(position_[i].x));
        agentCell_[i] = c;
        ++cellStart_[c];
    }
    // Each cell's end, then walking the agents backwards its start: every cell lists its agents in
    // increasing index.
    for (std::size_t c = 1; c <= cells; ++c) cellStart_[c] += cellStart_[c - 1];
    cellAgents_.resize(agents_.size());
    cellPositions_.resize(agents_.size());
    for (std::size_t k = agents_.size(); k-- > 0;) {
        const std::uint32_t i = agents_[k], at = --cellStart_[agentCell_[i]];
        cellAgents_[at] = i;
        cellPositions_[at] = ground(position_[i]);
    }
    // The walkers in the grid's order: neighbours stepped one after another share the cache.
    walkers_.clear();
    for (std::uint32_t i : cellAgents_)
        if (kind_[i] == kWalker) walkers_.push_back(i);
}

void OrcaRegionCrowd::plan(std::size_t i, Worker& w) {
    needsPath_[i] = 0;
    corners_[i].count = -1;
    dtPathCorridor& corridor = *corridor_[i];
    const dtPolyRef start = corridor.getFirstPoly();
    if (!start || !targetRef_[i]) return;
    int n = 0;
    w.query->findPath(start, targetRef_[i], &position_[i].x, &target_[i].x, &kFilter, w.path.data(), &n, kMaxPath);
    if (n == 0) {
        corridor.reset(start, &position_[i].x);
        return;
    }
    // A partial path (too long for the corridor, or the target out of reach) ends on its last polygon.
    glm::vec3 end = target_[i];
    if (w.path[std::size_t(n - 1)] != targetRef_[i]) w.query->closestPointOnPoly(w.path[std::size_t(n - 1)], &target_[i].x, &end.x, nullptr);
    corridor.setCorridor(&end.x, w.path.data(), n);
}

glm::vec2 OrcaRegionCrowd::steer(std::size_t i, Worker& w) {
    dtPathCorridor& corridor = *corridor_[i];
    if (!corridor.getFirstPoly()) return glm::vec2(0.0f);
    Corners& cached = corners_[i];
    float* corners = cached.at;
    unsigned char* flags = cached.flags;
    dtPolyRef polys[2];
    const glm::vec2 p = ground(position_[i]);
    const bool turn = (steps_ + slot_[i]) % 16 == 0;  // the occasional replanning, staggered over the walkers
    // The next two corners of the path, found again every kCornerEvery steps, or sooner when the
    // walker nears the first (a corner stays a point of the path as the walker moves along it).
    const glm::vec2 first(corners[0], corners[2]);
    if (cached.count < 0 || turn || (steps_ + slot_[i]) % kCornerEvery == 0 || cached.count == 0 ||
        glm::dot(first - p, first - p) < kCornerNear * kCornerNear)
        cached.count = std::int8_t(corridor.findCorners(corners, flags, polys, 2, w.query, &kFilter));
    int n = cached.count;
    // A partial path walked to near its end: the next part.
    if (turn && targetRef_[i] && corridor.getLastPoly() != targetRef_[i] && n > 0 && (flags[n - 1] & DT_STRAIGHTPATH_END)) {
        const glm::vec2 last(corners[3 * (n - 1)], corners[3 * (n - 1) + 2]);
        if (glm::dot(last - p, last - p) < 16.0f) {
            plan(i, w);
            n = cached.count = std::int8_t(corridor.findCorners(corners, flags, polys, 2, w.query, &kFilter));
        }
    }
    // Shortcuts through what the walker can see, as DetourCrowd's visibility optimisation does.
    if (turn && n > 0) {
        corridor.optimizePathVisibility(&corners[3 * (n - 1)], settings_.radius * 30.0f, w.query, &kFilter);
        n = cached.count = std::int8_t(corridor.findCorners(corners, flags, polys, 2, w.query, &kFilter));
    }
    if (n == 0) return glm::vec2(0.0f);
    // Towards the next corner, anticipating the one after (DetourCrowd's smooth steering).
    glm::vec2 direction = glm::vec2(corners[0], corners[2]) - p;
    if (n > 1) {
        glm::vec2 after = glm::vec2(corners[3], corners[5]) - p;
        const float afterLength = glm::length(after);
        if (afterLength > 0.001f) after /= afterLength;
        direction -= after * glm::length(direction) * 0.5f;
    }
    const float length = glm::length(direction);
    if (length < 1e-4f) return glm::vec2(0.0f);
    direction /= length;
    // Slowing down within two radii of the end.
    float speed = maxSpeed_[i];
    if (flags[n - 1] & DT_STRAIGHTPATH_END) {
        const float slow = 2.0f * settings_.radius;
        const float left = glm::length(glm::vec2(corners[3 * (n - 1)], corners[3 * (n - 1) + 2]) - p);
        if (left < slow) speed *= left / slow;
    }
    const glm::vec2 turnBy = turn_[i];
    return glm::vec2(turnBy.x * direction.x - turnBy.y * direction.y, turnBy.y * direction.x + turnBy.x * direction.y) * speed;
}

glm::vec2 OrcaRegionCrowd::avoid(std::size_t i, glm::vec2 preferred, float dt, Worker& w) {
    const orca::Body self{ground(position_[i]), ground(velocity_[i]), settings_.radius};
    std::size_t n = 0;
    // Walls first: they stay hard when the walkers' half-planes leave no room.
    dtLocalBoundary& boundary = *boundary_[i];
    const float wallRange = settings_.radius + maxSpeed_[i] * kWallHorizon + 0.5f;
    const glm::vec3 moved = position_[i] - glm::vec3(boundary.getCenter()[0], boundary.getCenter()[1], boundary.getCenter()[2]);
    if (corridor_[i]->getFirstPoly() && (boundary.getSegmentCount() == 0 || glm::dot(moved, moved) > 0.0625f * wallRange * wallRange))
        boundary.update(corridor_[i]->getFirstPoly(), &position_[i].x, 2.0f * wallRange, w.query, &kFilter);
    const orca::Body wallSelf{self.position, self.velocity, kWallClearance};
    for (int k = 0; k < boundary.getSegmentCount(); ++k) {
        const float* s = boundary.getSegment(k);
        if (orca::wallLine(wallSelf, glm::vec2(s[0], s[2]), glm::vec2(s[3], s[5]), kWallHorizon, dt, w.lines[n])) ++n;
    }
    const std::size_t walls = n;
    // The nearest neighbours, nearest first (ties by actor slot): the same set and order whatever
    // the thread count.
    struct Near {
        float d2;
        std::uint32_t slot, agent;
        bool operator<(const Near& o) const { return d2 < o.d2 || (d2 == o.d2 && slot < o.slot); }
    };
    Near nearest[kMaxNeighbours];
    int found = 0;
    const float range = settings_.radius * settings_.neighbourRange;
    // The density ahead (see kDensityRange), summed over every agent the grid finds, not only the
    // nearest kept for ORCA: in cells of a fixed order, the same sum with any thread count.
    const float speed = glm::length(preferred);
    const glm::vec2 heading = speed > 1e-4f ? preferred / speed : glm::vec2(0.0f);
    nextWay_[i] = heading;
    const float densityRange = std::min(kDensityRange, range);
    float crowding = 0.0f;
    // The cells the disc of the range reaches: a run of adjacent cells per row.
    const std::int32_t x0 = column(self.position.x - range), x1 = column(self.position.x + range);
    const std::int32_t z0 = row(self.position.y - range), z1 = row(self.position.y + range);
    for (std::int32_t z = z0; z <= z1; ++z) {
        const std::uint32_t first = cellStart_[std::size_t(z * columns_ + x0)], last = cellStart_[std::size_t(z * columns_ + x1 + 1)];
        for (std::uint32_t k = first; k < last; ++k) {
            const glm::vec2 d = cellPositions_[k] - self.position;
            const float d2 = glm::dot(d, d);
            if (d2 >= range * range) continue;
            const std::uint32_t j = cellAgents_[k];
            if (j == i) continue;
            if (d2 < densityRange * densityRange) {
                const float distance = std::sqrt(d2);
                if (glm::dot(d, heading) > kDensityCone * distance) crowding += 1.0f - distance / densityRange;
            }
            const Near candidate{d2, slot_[j], j};
            if (found == kMaxNeighbours) {
                if (!(candidate < nearest[kMaxNeighbours - 1])) continue;
                --found;
            }
            int at = found++;
            for (; at > 0 && candidate < nearest[at - 1]; --at) nearest[at] = nearest[at - 1];
            nearest[at] = candidate;
        }
    }
    // The pace people keep in the crowd ahead (Weidmann's fundamental diagram, as DenseSense, Best
    // et al. 2014, slows ORCA's agents): ORCA alone lets a dense crowd walk at full speed when
    // everyone moves alike. The weights' sum over the cone's weighted area, acos(c) R^2 / 3, is the
    // density; the cone's part beyond a wall counts as empty, so a walker entering a door sees the
    // few ahead of it in the door, not the crowd beside it.
    if (speed > 1e-4f) preferred *= weidmannShare(crowding / (std::acos(kDensityCone) * densityRange * densityRange / 3.0f));
    neighbourCount_[i] = std::uint8_t(found);
    for (int k = 0; k < found; ++k) neighbours_[i * kMaxNeighbours + std::size_t(k)] = nearest[k].agent;
    const bool held = glm::dot(self.velocity, self.velocity) < kHeldSpeed * kHeldSpeed && glm::dot(preferred, preferred) > kHeldWish * kHeldWish;
    for (int k = 0; k < found; ++k) {
        const std::size_t j = nearest[k].agent;
        const glm::vec2 other = ground(velocity_[j]);
        float share = 0.5f;
        if (held && glm::dot(other, other) < kHeldSpeed * kHeldSpeed && glm::dot(way_[j], heading) > kSameWay) {
            const glm::vec2 d = ground(position_[j]) - self.position;
            if (std::abs(glm::dot(d, heading)) < kAbreast * std::sqrt(nearest[k].d2)) {
                if (slot_[i] < slot_[j]) continue;  // the right of way: the other makes the room
                share = 1.0f;
            }
        }
        const float horizon = glm::dot(other, preferred) < 0.0f ? kHorizon : kAlongHorizon;
        w.lines[n++] = orca::agentLine(self, orca::Body{ground(position_[j]), other, settings_.radius}, horizon, dt, share);
    }
    return orca::solve(std::span<const orca::Line>(w.lines.data(), n), walls, preferred, maxSpeed_[i], w.scratch);
}

void OrcaRegionCrowd::update(float dt) {
    ++steps_;
    walkers_.clear();
    agents_.clear();
    for (std::uint32_t i = 0; i < kind_.size(); ++i) {
        if (kind_[i] == kFree) continue;
        agents_.push_back(i);
        if (kind_[i] == kWalker) walkers_.push_back(i);
    }
    if (settings_.avoidance) buildGrid();
    // New velocities from the state at the start of the step, then the moves along the corridors.
    const float maxChange = settings_.maxAcceleration * dt;
    forEachChunk(walkers_.size(), kGrain, [&](std::size_t, std::size_t begin, std::size_t end) {
        Worker& w = workers_.mine();
        for (std::size_t k = begin; k < end; ++k) {
            const std::size_t i = walkers_[k];
            if (needsPath_[i]) plan(i, w);
            const glm::vec2 preferred = steer(i, w);
            glm::vec2 v = settings_.avoidance ? avoid(i, preferred, dt, w) : preferred;
            // As fast as people change pace (DetourCrowd's acceleration limit).
            const glm::vec2 change = v - ground(velocity_[i]);
            const float changeLength = glm::length(change);
            if (changeLength > maxChange) v = ground(velocity_[i]) + change * (maxChange / changeLength);
            next_[i] = v;
        }
    });
    way_.swap(nextWay_);
    // Where each agent would be (ghosts move on as they went), then bodies that would still
    // interpenetrate by more than kSeparationSlack pushed apart, each taking half (DetourCrowd resolves
    // its collisions the same way): ORCA's velocities leave some overlap where its programs were
    // infeasible or a walker could not change pace fast enough. Read from one array, written to
    // another: the same with any thread count.
    for (std::uint32_t i : agents_) planned_[i] = ground(position_[i]) + (kind_[i] == kWalker ? next_[i] : ground(velocity_[i])) * dt;
    forEachChunk(walkers_.size(), kGrain, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const std::size_t i = walkers_[k];
            glm::vec2 push(0.0f);
            const float reach = 2.0f * settings_.radius;
            if (settings_.avoidance)
                for (std::size_t m = 0; m < neighbourCount_[i]; ++m) {
                    const std::size_t j = neighbours_[i * kMaxNeighbours + m];
                    const glm::vec2 d = planned_[i] - planned_[j];
                    const float distance2 = glm::dot(d, d);
                    if (distance2 >= reach * reach) continue;
                    const float distance = std::sqrt(distance2);
                    // Exactly on top of each other: apart along a direction fixed by their slots.
                    const glm::vec2 away = distance > 1e-4f ? d / distance : glm::vec2(slot_[i] < slot_[j] ? -1.0f : 1.0f, 0.0f);
                    if (reach - distance <= kSeparationSlack) continue;
                    push += away * (0.5f * (reach - distance - kSeparationSlack));
                }
            corrected_[i] = planned_[i] + push;
        }
    });
    forEachChunk(walkers_.size(), kGrain, [&](std::size_t, std::size_t begin, std::size_t end) {
        Worker& w = workers_.mine();
        for (std::size_t k = begin; k < end; ++k) {
            const std::size_t i = walkers_[k];
            dtPathCorridor& corridor = *corridor_[i];
            if (!corridor.getFirstPoly()) continue;
            const glm::vec3 to(corrected_[i].x, position_[i].y, corrected_[i].y);
            corridor.movePosition(&to.x, w.query, &kFilter);
            const float* p = corridor.getPos();
            position_[i] = glm::vec3(p[0], p[1], p[2]);
            // The velocity chosen, not the move the mesh allowed (as DetourCrowd keeps it): a walker
            // held at a wall still shows its neighbours where it is going.
            velocity_[i] = glm::vec3(next_[i].x, 0.0f, next_[i].y);
        }
    });
}

std::size_t OrcaRegionCrowd::bytes() const {
    std::size_t b = sizeof(*this);
    b += (position_.capacity() + velocity_.capacity() + target_.capacity()) * sizeof(glm::vec3) +
         (next_.capacity() + way_.capacity() + nextWay_.capacity()) * sizeof(glm::vec2);
    b += (planned_.capacity() + corrected_.capacity()) * sizeof(glm::vec2) + neighbours_.capacity() * sizeof(std::uint32_t) +
         neighbourCount_.capacity();
    b += corners_.capacity() * sizeof(Corners) + turn_.capacity() * sizeof(glm::vec2);
    b += maxSpeed_.capacity() * sizeof(float) + slot_.capacity() * sizeof(std::uint32_t) + kind_.capacity() + needsPath_.capacity();
    b += targetRef_.capacity() * sizeof(dtPolyRef) + free_.capacity() * sizeof(int);
    b += (corridor_.capacity() + boundary_.capacity()) * sizeof(void*);
    for (std::size_t i = 0; i < corridor_.size(); ++i)
        if (corridor_[i]) b += sizeof(dtPathCorridor) + kMaxPath * sizeof(dtPolyRef) + sizeof(dtLocalBoundary);
    b += (walkers_.capacity() + agents_.capacity() + cellStart_.capacity() + cellAgents_.capacity() + agentCell_.capacity()) *
         sizeof(std::uint32_t) + cellPositions_.capacity() * sizeof(glm::vec2);
    return b;
}

}  // namespace throng::sim::locomotion
