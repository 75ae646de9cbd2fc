#pragma once
// Internal to sim: a region's crowd kept apart by ORCA (sim/OrcaSolver). Navigation stays Detour's:
// each walker follows its own path corridor (dtPathCorridor) and sees the walls near it
// (dtLocalBoundary, the mesh's boundary edges), and this crowd does the rest. Data-oriented: agents
// are flat arrays indexed by agent; neighbours come from a uniform grid rebuilt in place each step;
// nothing is allocated per step once the arrays have grown. Each walker's new velocity depends only
// on the state at the start of the step, and its neighbours are taken in a fixed order (distance,
// then actor slot), so the result is the same with 1 or N threads: the walkers are shared out on
// oneTBB, each thread with its own navigation query.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "RegionCrowd.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/OrcaSolver.h"

class dtNavMeshQuery;
class dtPathCorridor;
class dtLocalBoundary;

namespace throng::sim::locomotion {

/// Each thread's navigation query and scratch, shared by every ORCA crowd of a Locomotion: a thread
/// runs one crowd's chunk at a time, so a crowd's step never meets another use of its thread's entry.
class OrcaWorkers {
public:
    /// One thread's entry.
    struct Worker {
        dtNavMeshQuery* query = nullptr;   ///< its own navigation query
        std::vector<dtPolyRef> path;       ///< room for a planned path
        std::vector<orca::Line> lines;     ///< a walker's half-planes
        std::vector<orca::Line> scratch;   ///< the solver's scratch
    };
    OrcaWorkers() = default;
    ~OrcaWorkers();
    OrcaWorkers(const OrcaWorkers&) = delete;
    OrcaWorkers& operator=(const OrcaWorkers&) = delete;
    /// Makes room for every thread that may run the next step's chunks (call outside any parallel loop).
    void prepare(const NavMesh& nav);
    /// The calling thread's entry. Throws std::logic_error when prepare() did not make room for it.
    Worker& mine();
    /// Bytes the entries hold, their queries' node pools included.
    std::size_t bytes() const;

private:
    std::vector<Worker> workers_;
};

/// A region's walkers moved by ORCA along Detour path corridors.
class OrcaRegionCrowd final : public RegionCrowd {
public:
    /// The time horizon for a walker coming towards another (its velocity against the other's way),
    /// seconds: how early two walkers meeting start to give way (long enough for lanes to form).
    static constexpr float kHorizon = 2.0f;
    /// The time horizon for a walker going the other's way, across it, or standing, seconds. Short:
    /// with 2 s, walkers pressing towards a door each hold back for the others, and the crowd jams
    /// before it (an arch whose walkers all wait for one another).
    static constexpr float kAlongHorizon = 0.25f;
    /// The time horizon for walls, seconds.
    static constexpr float kWallHorizon = 0.5f;
    /// How near the centre of a walker may come to the mesh's boundary, metres (the mesh is already
    /// eroded by the body's radius).
    static constexpr float kWallClearance = 0.05f;
    /// How far ahead a walker judges the crowd's density, metres: the walkers within this distance
    /// (at most the neighbour range) and within kDensityCone of its way, weighted 1 at its centre
    /// falling linearly to 0 at this distance.
    static constexpr float kDensityRange = 2.0f;
    /// The cone of kDensityRange: the cosine of its half angle (60 degrees; the walkers beside a
    /// door are not in the way of one entering it).
    static constexpr float kDensityCone = 0.5f;
    /// Right of way between walkers held back abreast (after Curtis et al. 2013, "Right of way:
    /// asymmetric agent interactions in crowds"): two walkers slower than this, m/s, ...
    static constexpr float kHeldSpeed = 0.5f;
    /// ...each wanting to go faster than this, m/s (after the density ahead slowed it)...
    static constexpr float kHeldWish = 0.6f;
    /// ...going the same way (the cosine between their ways above this)...
    static constexpr float kSameWay = 0.8f;
    /// ...and abreast (the other's direction within 45 degrees of square to the walker's way: the
    /// cosine to its way below this) do not each wait for the other: the walker with the lower actor
    /// slot goes on as if the other were not there, the other makes all the room. With ORCA's half
    /// each, two walkers at the mouth of a door hold each other back for seconds (an arch), and the
    /// bottleneck passes half the experiments' flow.
    static constexpr float kAbreast = 0.7f;
    /// Bodies interpenetrating by less than this after a move are left to ORCA, metres; deeper
    /// overlaps are pushed apart. Pushing the shallow ones too makes two groups walking at each other
    /// push back and forth until they jam (the counter-flow scenario).
    static constexpr float kSeparationSlack = 0.03f;
    /// A walker's next corners are found again every this many steps...
    static constexpr int kCornerEvery = 4;
    /// ...or sooner, once it is this near the first, metres.
    static constexpr float kCornerNear = 0.5f;
    /// At most this many of the nearest neighbours enter a walker's program.
    static constexpr int kMaxNeighbours = 10;
    /// Polygons a path corridor holds (as DetourCrowd's); a longer path is walked in parts, each
    /// planned when the walker comes near the end of the last.
    static constexpr int kMaxPath = 256;

    /// A crowd with `settings`, using `query` outside its steps and `workers` inside them (all the
    /// caller's, outliving it).
    OrcaRegionCrowd(const Locomotion::Settings& settings, dtNavMeshQuery& query, OrcaWorkers& workers);
    ~OrcaRegionCrowd() override;
    OrcaRegionCrowd(const OrcaRegionCrowd&) = delete;
    OrcaRegionCrowd& operator=(const OrcaRegionCrowd&) = delete;

    int add(std::uint32_t slot, const float* position, const float* velocity, float maxSpeed, bool ghost) override;
    void remove(int agent) override;
    void requestTarget(int agent, dtPolyRef ref, const float* target) override;
    void update(float dt) override;
    glm::vec3 position(int agent) const override { return position_[std::size_t(agent)]; }
    glm::vec3 velocity(int agent) const override { return velocity_[std::size_t(agent)]; }
    std::size_t bytes() const override;

private:
    enum : std::uint8_t { kFree = 0, kWalker = 1, kGhost = 2 };
    // The next two corners of a walker's path (-1: to be found).
    struct Corners {
        float at[6] = {};
        unsigned char flags[2] = {};
        std::int8_t count = -1;
    };
    using Worker = OrcaWorkers::Worker;

    void buildGrid();
    // The grid column or row of a coordinate (x or z), clamped to the grid.
    std::int32_t column(float x) const;
    std::int32_t row(float z) const;
    // Plans agent i's path to its target from where it stands.
    void plan(std::size_t i, Worker& w);
    // Agent i's preferred velocity along its corridor (zero when it has arrived or has no path).
    glm::vec2 steer(std::size_t i, Worker& w);
    // Agent i's new velocity: `preferred` slowed to the speed people keep in the density ahead of it,
    // then the nearest to that which ORCA allows.
    glm::vec2 avoid(std::size_t i, glm::vec2 preferred, float dt, Worker& w);

    const Locomotion::Settings& settings_;
    dtNavMeshQuery& query_;  // for add(), outside the step
    OrcaWorkers& workers_;
    // Agents, by index.
    std::vector<glm::vec3> position_, velocity_, target_;
    std::vector<glm::vec2> next_;               // the velocity chosen this step
    // Each walker's way (its preferred direction, unit, or zero) as its neighbours see it: the last
    // step's, read while this step's is written to nextWay_ (swapped after): the same with any thread count.
    std::vector<glm::vec2> way_, nextWay_;
    std::vector<glm::vec2> planned_, corrected_;  // where it would be, and after bodies are pushed apart
    std::vector<std::uint32_t> neighbours_;       // this step's nearest, kMaxNeighbours per agent
    std::vector<std::uint8_t> neighbourCount_;
    std::vector<Corners> corners_;   // the next corners, found every kCornerEvery steps
    std::vector<glm::vec2> turn_;    // cosine and sine of each walker's small fixed turn
    std::vector<float> maxSpeed_;
    std::vector<std::uint32_t> slot_;
    std::vector<std::uint8_t> kind_, needsPath_;
    std::vector<dtPolyRef> targetRef_;
    std::vector<std::unique_ptr<dtPathCorridor>> corridor_;   // walkers' (kept for the index's next walker)
    std::vector<std::unique_ptr<dtLocalBoundary>> boundary_;  // walkers' walls near them
    std::vector<int> free_;
    // This step's walkers and every agent, in index order.
    std::vector<std::uint32_t> walkers_, agents_;
    // The neighbour grid: square cells over the agents' bounds, row by row, each cell's agents (in
    // increasing index) at [cellStart_[c], cellStart_[c + 1]) of cellAgents_, with their positions,
    // so that the cells of one row a search reads lie side by side in memory.
    float cellSize_ = 1.0f;
    glm::vec2 gridOrigin_{0.0f};
    std::int32_t columns_ = 1, rows_ = 1;
    std::vector<std::uint32_t> cellStart_, cellAgents_, agentCell_;
    std::vector<glm::vec2> cellPositions_;
    std::uint64_t steps_ = 0;
};

}  // namespace throng::sim::locomotion
