#pragma once
// The operation categories of Table 1 of Rodriguez et al. 2010 (seed 002), used to account the
// scenegraph's work in FMULT units by what the work is for.

#include <array>
#include <cstdint>
#include <string_view>

namespace throng {

/// What a counted operation is for, as in Table 1 of the cost model. The operation counts (NO_xx)
/// go to the first six; for NO_01 to NO_03 the cost of the DOF values (CO_xxa, the behaviour) is kept
/// apart from the cost of the matrix (CO_xxb) so that a scene's real AverageCost can be measured.
enum class OpCategory : std::uint8_t {
    SkeletonMatrix,         ///< NO_01, CO_01b: matrix of an articulation (a Skeleton node or generic Transform).
    RefpointMatrix,         ///< NO_02, CO_02b: matrix of an actor's Reference Point.
    SkeletonRootMatrix,     ///< NO_03, CO_03b: matrix of an actor's Skeleton Root.
    BsphereRecompute,       ///< NO_04a: a bounding sphere recomputed from its descendants.
    BsphereFrustumTest,     ///< NO_04b: a bounding sphere tested against the frustum.
    LodDistance,            ///< NO_05: a distance computed for level of detail selection.
    SkeletonDofValues,      ///< CO_01a: DOF values of articulations (behaviour).
    RefpointDofValues,      ///< CO_02a: DOF values of Reference Points (behaviour).
    SkeletonRootDofValues,  ///< CO_03a: DOF values of Skeleton Roots (behaviour).
};

/// Number of categories in OpCategory.
inline constexpr std::size_t kOpCategoryCount = 9;

/// The paper's name of a category ("NO_01" ... "NO_05", then "CO_01a", "CO_02a", "CO_03a").
constexpr std::string_view opCategoryName(OpCategory c) {
    constexpr std::array<std::string_view, kOpCategoryCount> names = {
        "NO_01", "NO_02", "NO_03", "NO_04a", "NO_04b", "NO_05", "CO_01a", "CO_02a", "CO_03a"};
    return names[static_cast<std::size_t>(c)];
}

}  // namespace throng
