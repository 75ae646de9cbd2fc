#pragma once
// Internal to sim: the region stepper of Locomotion. The ground is divided into fixed regions (a
// RegionGrid), each stepped by its own crowd (DetourCrowd, or ORCA along Detour's corridors: the
// scene's avoidance model) and navigation query, in parallel. An agent near
// a border is seen by the neighbouring region as a ghost (a copy of it at the start of the step,
// which that region never moves); an agent that crosses a border is handed over at the end of the
// step, in order of actor slot. Far regions may step less often. Ghost export and import and the
// handover are separate steps over flat records, so the caller delivers them: in one process
// (deliverGhosts, deliverHandovers), or across ranks (RankExchange).

#include <cstdint>
#include <span>
#include <vector>

#include <DetourNavMesh.h>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <memory>

#include "OrcaRegionCrowd.h"
#include "RegionCrowd.h"
#include "WalkerState.h"
#include "throng/sim/Locomotion.h"

class dtNavMeshQuery;

namespace throng::sim::locomotion {

/// The regions of a Locomotion and how each steps its walkers.
class RegionStepper {
public:
    /// One region: its crowd and query, the actors it owns (increasing slots) and the records it
    /// exchanges with the others during a step.
    struct Region {
        std::unique_ptr<RegionCrowd> crowd;       ///< its crowd
        dtNavMeshQuery* query = nullptr;          ///< its navigation query
        int capacity = 0;                         ///< agents a DetourCrowd has room for at first, ghosts included
        std::vector<std::uint32_t> owned;         ///< the walkers it steps, increasing slots
        std::vector<std::uint32_t> scratch;       ///< room to merge `owned` with arrivals
        std::vector<GhostRecord> ghostsOut;       ///< its agents other regions see this step
        std::vector<GhostRecord> ghostsIn;        ///< the other regions' agents it sees
        std::vector<int> ghostAgents;             ///< the ghosts' agents in its crowd, during the step
        std::vector<HandoverRecord> leaving;      ///< its agents that crossed into another region
        std::vector<HandoverRecord> arriving;     ///< agents that crossed into it
    };

    /// The regions of `settings` on `nav`, stepping `walkers` (one per actor of `actors`), the
    /// region owning each in `regionOf`. All four stay the caller's.
    RegionStepper(const NavMesh& nav, const Locomotion::Settings& settings, std::span<const Locomotion::Actor> actors,
                  std::span<WalkerState> walkers, std::span<std::uint32_t> regionOf);
    ~RegionStepper();
    RegionStepper(const RegionStepper&) = delete;
    RegionStepper& operator=(const RegionStepper&) = delete;

    /// Gives every walker to the region it stands in and sizes each region's crowd. Throws
    /// std::invalid_argument for cells narrower than the collision range, std::runtime_error for a
    /// region that starts with more agents than DetourCrowd can number.
    void place();
    /// Makes the crowds of regions [first, end), in parallel, their walkers added and sent walking.
    void start(std::uint32_t first, std::uint32_t end);
    /// Readies the threads' scratch of the next step (call before stepping regions in parallel).
    void prepareStep();
    /// Bytes the regions' crowds and records hold.
    std::size_t bytes() const;
    /// Number of regions.
    std::uint32_t count() const { return std::uint32_t(regions_.size()); }
    /// Region `r`.
    Region& region(std::uint32_t r) { return regions_[r]; }
    /// Region `r`.
    const Region& region(std::uint32_t r) const { return regions_[r]; }

    /// Decides which of regions [first, end) step now, after `dt` more seconds: every one, unless
    /// the settings let regions far from `viewpoint` step less often. Returns the walkers deferred.
    std::size_t chooseStepping(std::uint32_t first, std::uint32_t end, double dt, glm::vec3 viewpoint);
    /// Lists region `r`'s agents near another region (its ghostsOut).
    void exportGhosts(std::uint32_t r);
    /// One process: empties every region's ghostsIn, then fills it from the others' ghostsOut, in
    /// order of sending region and slot. Returns the ghosts delivered.
    std::size_t deliverGhosts();
    /// Steps region `r` by `dt` seconds (or, waiting for its turn, carries its walkers on), its
    /// ghosts standing in the way.
    void stepRegion(std::uint32_t r, float dt);
    /// Lists region `r`'s agents that now stand in another region (its leaving) and removes them.
    void exportHandovers(std::uint32_t r);
    /// One process: empties every region's arriving, then fills it from the others' leaving.
    /// Returns the agents handed over.
    std::size_t deliverHandovers();
    /// Adds region `r`'s arrivals to its crowd (in order of slot) and updates what it owns.
    void importHandovers(std::uint32_t r);

private:
    int addAgent(Region& region, std::uint32_t r, std::uint32_t slot, const float* position, const float* velocity, bool ghost);
    void requestTarget(Region& region, std::uint32_t slot);
    // The nearest point of the mesh to `p` within `extents`, with the region's own query (thread-safe
    // across regions); 0 and `snapped` untouched when there is none.
    static dtPolyRef nearestOnMesh(Region& region, const glm::vec3& p, const glm::vec3& extents, glm::vec3& snapped);
    // A walker of a periodic corridor past its goal's line re-enters one period back.
    void wrapAround(Region& region, std::uint32_t r, std::uint32_t slot);
    void newDestination(Region& region, std::uint32_t slot);
    void startRegion(std::uint32_t r);
    void importGhosts(std::uint32_t r);

    const NavMesh& nav_;
    const Locomotion::Settings& settings_;
    std::span<const Locomotion::Actor> actors_;
    std::span<WalkerState> state_;
    std::span<std::uint32_t> regionOf_;
    std::vector<Region> regions_;
    // Far regions: each region's bounds, the time since it last stepped, whether it steps in this
    // step, and the steps so far (which far regions take their turn).
    std::vector<glm::dvec4> regionBounds_;
    std::vector<double> pending_;
    std::vector<std::uint8_t> stepping_;
    std::uint64_t steps_ = 0;
    OrcaWorkers orcaWorkers_;  // ORCA crowds' per-thread queries and scratch
};

}  // namespace throng::sim::locomotion
