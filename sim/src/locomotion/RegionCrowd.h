#pragma once
// Internal to sim: what the region stepper asks of a region's crowd, whichever model moves it. A
// crowd holds the region's walkers and, during a step, the ghosts of its neighbours' walkers; it
// follows each walker's path on the navigation mesh and keeps walkers apart by its avoidance model:
// DetourCrowd's sampled velocities (DetourRegionCrowd) or ORCA's half-planes (OrcaRegionCrowd). One
// virtual call per walker added, moved or read, none inside a step's per-walker loops.

#include <cstddef>
#include <cstdint>

#include <DetourNavMesh.h>
#include <glm/vec3.hpp>

namespace throng::sim::locomotion {

/// A region's walkers and how they move together.
class RegionCrowd {
public:
    virtual ~RegionCrowd() = default;
    /// Adds actor `slot` at `position` (onto the mesh), moving at `velocity` (null: standing) no
    /// faster than `maxSpeed`. A ghost only stands in the way: it is not steered, and moves on at its
    /// velocity. Returns the agent's index, or -1 when the crowd is full.
    virtual int add(std::uint32_t slot, const float* position, const float* velocity, float maxSpeed, bool ghost) = 0;
    /// Removes an agent; its index may be given to a later one.
    virtual void remove(int agent) = 0;
    /// Sends an agent walking to `target`, which lies on polygon `ref`.
    virtual void requestTarget(int agent, dtPolyRef ref, const float* target) = 0;
    /// Moves every walker by `dt` seconds, the ghosts in the way.
    virtual void update(float dt) = 0;
    /// Where an agent stands.
    virtual glm::vec3 position(int agent) const = 0;
    /// How an agent moves, m/s.
    virtual glm::vec3 velocity(int agent) const = 0;
    /// Bytes the crowd holds (its agents, paths, neighbour grid and scratch).
    virtual std::size_t bytes() const = 0;
};

}  // namespace throng::sim::locomotion
