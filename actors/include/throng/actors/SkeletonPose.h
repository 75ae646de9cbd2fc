#pragma once
// Stateless jobs on one actor's pose (in the manner of ozz-animation): which nodes are active at a
// distance, local and model transforms from DOF values, and the hierarchy of internal bounding
// spheres. Inputs are plain spans; outputs are spans the caller owns. All work in the Skeleton Root
// frame; only active nodes are touched.

#include <cstdint>
#include <span>

#include "throng/actors/Affine.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

/// Sets active[i] = 1 for nodes whose deactivation distance exceeds the (scaled) eye distance whose
/// square is `distance2`, and whose parent is active; 0 otherwise. `active` must hold nodeCount()
/// flags. Returns the number of active nodes.
std::size_t computeActiveNodes(const ActorTemplate& tmpl, double distance2, std::span<std::uint8_t> active);

/// Skinning matrices of `skin` (model space, bind to posed): palette[k] = model[n] * inverseBind(n)
/// for its joint k at node n, or, when n is inactive, for n's nearest active ancestor (a
/// deactivated joint moves rigidly with it, as bound). Joints with no active ancestor keep the
/// bind pose. `palette` must hold skin.joints.size() matrices.
void computeSkinPalette(const ActorTemplate& tmpl, const Skin& skin, std::span<const Affine> model,
                        std::span<const std::uint8_t> active, std::span<glm::mat4> palette, OpTally* ops = nullptr);

/// Square of the distance that selects an actor's detail: |Skeleton Root - eye|^2 times the LOD
/// scale squared, divided by the priority squared. Every LOD decision of both processing methods
/// goes through it, so they agree to the last bit. Costs 8 FMULT (NO_05) plus the scaling.
double detailDistanceSquared(const Mat4& skeletonRootWorld, const Vec3& eye, double lodScale2, float priority,
                             OpTally* ops = nullptr);

/// Distance from the eye to the Skeleton Root, the actor's `eyeDistance` (3 mults, 5 adds, 1 sqrt;
/// NO_05 with detailDistanceSquared).
double eyeDistance(const Mat4& skeletonRootWorld, const Vec3& eye, OpTally* ops = nullptr);

/// The Skeleton Root's transform relative to the Reference Point as a matrix (18 mults, 15 adds).
Mat4 rootPoseMatrix(const RootPose& root, OpTally* ops = nullptr);

/// World matrix of a node: the Skeleton Root's world matrix times the node's `model` transform,
/// written into `world` (the same product as composeAffine(skeletonRootWorld, model.toDMat4()),
/// without building either 4x4 operand or the result apart).
void nodeWorldMatrix(const Mat4& skeletonRootWorld, const Affine& model, Mat4& world, OpTally* ops = nullptr);

/// World sphere of a part: `local` (in its node's frame) placed by the node's `model` transform,
/// then by the Skeleton Root's world matrix. Both processing methods test parts with it.
BoundingSphere partWorldSphere(const BoundingSphere& local, const Affine& model, const Mat4& skeletonRootWorld,
                               OpTally* ops = nullptr);

/// Writes the rest values of the DOFs of the nodes flagged in `active` (every node when empty)
/// into `dofs`, leaving other nodes' values untouched.
void writeRestPose(const ActorTemplate& tmpl, std::span<const std::uint8_t> active, std::span<float> dofs);

/// Local transform of `node` from its DOF values (`values` points at the node's first value),
/// each clamped to its limits.
Affine nodeLocalTransform(const SkeletonNode& node, const float* values, OpTally* ops = nullptr);

/// Model transforms (node frame to Skeleton Root frame) of the active nodes (every node when
/// `active` is empty), parents first; entries of inactive nodes are left untouched. `model` must
/// hold nodeCount() entries. Returns the number of nodes computed.
std::size_t computeModelTransforms(const ActorTemplate& tmpl, std::span<const float> dofs,
                                   std::span<const std::uint8_t> active, std::span<Affine> model,
                                   OpTally* ops = nullptr);

/// Internal bounding spheres in the Skeleton Root frame for the active nodes (all when `active` is
/// empty): geometry[i] is node i's geometry sphere placed by model[i]; subtree[i] holds geometry[i]
/// and the subtree spheres of its active children. Returns the actor's whole internal bound (its
/// actor-level geometry included). Spans must hold nodeCount() entries.
BoundingSphere computeInternalSpheres(const ActorTemplate& tmpl, std::span<const Affine> model,
                                      std::span<const std::uint8_t> active, std::span<BoundingSphere> geometry,
                                      std::span<BoundingSphere> subtree, OpTally* ops = nullptr);

}  // namespace throng
