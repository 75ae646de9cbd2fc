#pragma once
// A skin of an actor template: which Skeleton nodes deform a skinned mesh, in the order its vertex
// joint indices refer to. Each node's inverse bind matrix is SkeletonNode::inverseBind.

#include <cstdint>
#include <string>
#include <vector>

namespace throng {

/// Joints of a skinned mesh.
struct Skin {
    std::string name;                   ///< for messages
    std::vector<std::uint32_t> joints;  ///< skin joint k is Skeleton node joints[k]
};

}  // namespace throng
