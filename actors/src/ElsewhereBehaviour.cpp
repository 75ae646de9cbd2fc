// Actors another process simulates and shows (ElsewhereBehaviour.h).

#include "throng/actors/ElsewhereBehaviour.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace throng {
namespace {

[[noreturn]] void neverHere(const char* call, std::uint32_t slot) {
    throw std::logic_error(std::string("ElsewhereBehaviour::") + call + ": actor slot " + std::to_string(slot) +
                           " is simulated by another process and never present here");
}

}  // namespace

Mat4 ElsewhereBehaviour::referencePoint(std::uint32_t slot, const FrameContext&, OpTally*) { neverHere("referencePoint", slot); }

RootPose ElsewhereBehaviour::skeletonRoot(std::uint32_t slot, double, int, OpTally*) { neverHere("skeletonRoot", slot); }

void ElsewhereBehaviour::pose(std::uint32_t slot, double, int, const ActorTemplate&, std::span<const std::uint8_t>, std::span<float>,
                              OpTally*) {
    neverHere("pose", slot);
}

bool ElsewhereBehaviour::presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const {
    std::fill(present.begin(), present.begin() + std::ptrdiff_t(slots.size()), std::uint8_t{0});
    return false;
}

}  // namespace throng
