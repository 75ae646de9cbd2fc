#pragma once
// The description of one articulation of an actor template (seed 002 §3): its place in the
// hierarchy, rest transform, DOFs with limits, deactivation distance (skeletal LOD) and geometry
// (its vaLod levels). Shared by every clone; per-actor values live in the Crowd.

#include <limits>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "throng/actors/Dof.h"
#include "throng/actors/VaLod.h"
#include "throng/scenegraph/BoundingSphere.h"

namespace throng {

/// One articulation (joint) of a template's skeleton.
struct SkeletonNode {
    std::string name;                     ///< unique within the template
    int parent = -1;                      ///< index of the parent node, or -1 under the Skeleton Root
    glm::vec3 restTranslation{0.0f};      ///< offset from the parent's frame
    glm::quat restRotation{1, 0, 0, 0};   ///< rotation before the DOFs
    glm::vec3 restScale{1.0f};            ///< scale before the DOFs
    std::vector<Dof> dofs;                ///< degrees of freedom, applied in order
    /// Beyond this (scaled) eye distance the node is not processed: DOFs not evaluated, matrix not
    /// built, subtree not traversed (seed 002 §5.2). Infinite: always active.
    double deactivationDistance = std::numeric_limits<double>::infinity();
    VaLod geometry;                       ///< rigid geometry drawn in this node's frame
    /// Sphere (node frame) of what this node moves, for internal culling. Left empty, it is the
    /// bound of `geometry`; skinned templates set it from the vertices the joint dominates.
    BoundingSphere geometrySphere;
    glm::mat4 inverseBind{1.0f};          ///< skinning: model space to this joint's rest frame
};

}  // namespace throng
