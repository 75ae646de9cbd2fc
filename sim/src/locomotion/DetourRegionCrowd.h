#pragma once
// Internal to sim: a region's crowd moved by DetourCrowd: its path corridors and steering, and (when
// the scene declares avoidance) its sampled velocity obstacles and separation.

#include <memory>

#include "RegionCrowd.h"
#include "throng/sim/Locomotion.h"

class dtCrowd;

namespace throng::sim::locomotion {

/// A DetourCrowd of fixed capacity.
class DetourRegionCrowd final : public RegionCrowd {
public:
    /// A crowd of at most `capacity` agents, ghosts included, on `nav` with `settings`. Throws
    /// std::runtime_error when DetourCrowd cannot be made.
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
    const Locomotion::Settings& settings_;
    dtCrowd* crowd_ = nullptr;
    int capacity_ = 0;
};

}  // namespace throng::sim::locomotion
