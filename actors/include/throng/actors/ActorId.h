#pragma once
// Identifies an actor within its Crowd.

#include <cstdint>

namespace throng {

/// Index of an actor in its Crowd's arrays.
using ActorId = std::uint32_t;

}  // namespace throng
