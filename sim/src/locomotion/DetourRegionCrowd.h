#pragma once
// Internal to sim: a region's crowd moved by DetourCrowd: its path corridors and steering, and (when
// the scene declares avoidance) its sampled velocity obstacles and separation. DetourCrowd allocates
// every agent it may hold up front; this crowd starts a little above what the region needs and, when
// full, moves its agents into one twice the size (each keeps its place, velocity and target; agents
// are known by handles that stay the same).

#include <memory>
#include <vector>

#include "RegionCrowd.h"
#include "throng/sim/Locomotion.h"

class dtCrowd;
struct dtCrowdAgentParams;

namespace throng::sim::locomotion {

/// A DetourCrowd of fixed capacity.
class DetourRegionCrowd final : public RegionCrowd {
public:
    /// Most agents a crowd holds: DetourCrowd numbers them with 16 bits.
    static constexpr int kMostAgents = 65000;
    /// A crowd with room for `capacity` agents at first, ghosts included, on `nav` with `settings`;
    /// it grows up to kMostAgents. Throws std::runtime_error when DetourCrowd cannot be made.
    DetourRegionCrowd(const NavMesh& nav, const Locomotion::Settings& settings, int capacity);
    ~DetourRegionCrowd() override;
    DetourRegionCrowd(const DetourRegionCrowd&) = delete;
    DetourRegionCrowd& operator=(const DetourRegionCrowd&) = delete;

    int add(std::uint32_t slot, const float* position, const float* velocity, float maxSpeed, bool ghost) override;
    void remove(int agent) override;
    void requestTarget(int agent, dtPolyRef ref, const float* target) override;
    void update(float dt) override;
    glm::vec3 position(int agent) const override;
    glm::vec3 velocity(int agent) const override;
    std::size_t bytes() const override;

private:
    // What an agent is made again from when the crowd grows.
    struct Kept {
        float maxSpeed = 0.0f;
        bool ghost = false;
        dtPolyRef targetRef = 0;  // 0: no target asked for
        float target[3] = {};
    };
    // A DetourCrowd for `capacity` agents with this crowd's sampling.
    dtCrowd* makeCrowd(int capacity) const;
    // DetourCrowd's parameters for an agent.
    void fillParams(const Kept& kept, dtCrowdAgentParams& params) const;
    // Moves every agent into a crowd twice the size; false when the crowd is as large as it may be.
    bool grow();

    const NavMesh& nav_;
    const Locomotion::Settings& settings_;
    dtCrowd* crowd_ = nullptr;
    int capacity_ = 0;
    std::vector<int> agentOf_;   // DetourCrowd's index of each handle, -1 when free
    std::vector<Kept> kept_;     // by handle
    std::vector<int> freeHandles_;
};

}  // namespace throng::sim::locomotion
