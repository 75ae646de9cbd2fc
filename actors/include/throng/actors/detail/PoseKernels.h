#pragma once
// The pose jobs of SkeletonPose.h (local and model transforms, internal spheres, skin palettes,
// detail distance, Skeleton Root matrix), written once over the scalar type: SkeletonPose.cpp
// compiles them for float (actor space) and double (world space), the FMULT tests for a counting
// type. Comparisons are counted as additions (std::clamp makes two: libstdc++ takes a max, then a
// min); sine and cosine are priced as square roots.

#include <algorithm>
#include <cstdint>
#include <span>

#include <glm/gtc/quaternion.hpp>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/Affine.h"
#include "throng/actors/RootPose.h"
#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/ItemTransform.h"
#include "throng/scenegraph/OpTally.h"
#include "throng/scenegraph/detail/ScalarMath.h"
#include "throng/scenegraph/detail/TransformKernels.h"

namespace throng::detail {

/// Skinning matrices (see throng::computeSkinPalette): 64 mults, 48 adds per joint with an active
/// node.
template <class S>
void computeSkinPalette(const ActorTemplate& tmpl, const Skin& skin, std::span<const BasicAffine<S>> model,
                        std::span<const std::uint8_t> active, std::span<glm::mat<4, 4, S, glm::defaultp>> palette,
                        OpTally* ops) {
    using M = glm::mat<4, 4, S, glm::defaultp>;
    const auto nodes = tmpl.nodes();
    for (std::size_t k = 0; k < skin.joints.size(); ++k) {
        int n = static_cast<int>(skin.joints[k]);
        while (n >= 0 && !active.empty() && !active[static_cast<std::size_t>(n)]) n = nodes[static_cast<std::size_t>(n)].parent;
        if (n < 0) {
            palette[k] = M(S(1));
            continue;
        }
        const auto node = static_cast<std::size_t>(n);
        palette[k] = model[node].toMat4() * convertTo<M>(nodes[node].inverseBind);
        THRONG_TALLY(ops, 64, 48, 0, 0);
    }
}

/// |Skeleton Root - eye|^2 * lodScale2 / priority^2 (see throng::detailDistanceSquared).
template <class W>
W detailDistanceSquared(const glm::mat<4, 4, W, glm::defaultp>& skeletonRootWorld,
                        const glm::vec<3, W, glm::defaultp>& eye, W lodScale2, W priority, OpTally* ops) {
    const glm::vec<3, W, glm::defaultp> d = glm::vec<3, W, glm::defaultp>(skeletonRootWorld[3]) - eye;
    THRONG_TALLY(ops, 5, 5, 1, 0);  // the distance (8 FMULT), then the scale and the priority
    return glm::dot(d, d) * lodScale2 / (priority * priority);
}

/// |Skeleton Root - eye| (see throng::eyeDistance): 3 mults, 5 adds, 1 sqrt.
template <class W>
W eyeDistance(const glm::mat<4, 4, W, glm::defaultp>& skeletonRootWorld, const glm::vec<3, W, glm::defaultp>& eye,
              OpTally* ops) {
    THRONG_TALLY(ops, 3, 5, 0, 1);
    return glm::length(glm::vec<3, W, glm::defaultp>(skeletonRootWorld[3]) - eye);
}

/// The Skeleton Root's matrix relative to the Reference Point (18 mults, 15 adds).
template <class S>
glm::mat<4, 4, Wide<S>, glm::defaultp> rootPoseMatrix(const BasicRootPose<S>& root, OpTally* ops) {
    using W = Wide<S>;
    return matrixFromDofs(glm::vec<3, W, glm::defaultp>(root.translation), glm::qua<W, glm::defaultp>(root.orientation),
                          glm::vec<3, W, glm::defaultp>(W(1)), ops);
}

/// World matrix of a node (see throng::nodeWorldMatrix): composeAffine(skeletonRootWorld,
/// model.toDMat4()) term for term, written straight into `world` (36 mults, 27 adds).
template <class S>
void nodeWorldMatrix(const glm::mat<4, 4, Wide<S>, glm::defaultp>& skeletonRootWorld, const BasicAffine<S>& model,
                     glm::mat<4, 4, Wide<S>, glm::defaultp>& world, OpTally* ops) {
    using W = Wide<S>;
    const auto& a = skeletonRootWorld;
    for (int c = 0; c < 3; ++c) {
        const W b0 = W(model.linear[c][0]), b1 = W(model.linear[c][1]), b2 = W(model.linear[c][2]);
        for (int row = 0; row < 3; ++row) world[c][row] = a[0][row] * b0 + a[1][row] * b1 + a[2][row] * b2;
        world[c][3] = W(0);
    }
    const W t0 = W(model.translation[0]), t1 = W(model.translation[1]), t2 = W(model.translation[2]);
    for (int row = 0; row < 3; ++row) world[3][row] = a[0][row] * t0 + a[1][row] * t1 + a[2][row] * t2 + a[3][row];
    world[3][3] = W(1);
    THRONG_TALLY(ops, 36, 27, 0, 0);
}

/// The same product written as a draw item's transform: the linear part computed in double as
/// nodeWorldMatrix does, then rounded to float, and the translation in double (36 mults, 27 adds).
/// Computed in registers straight into `world` (a matrix built apart and read back would stall).
inline void nodeWorldTransform(const Mat4& skeletonRootWorld, const Affine& model, ItemTransform& world, OpTally* ops) {
    const Mat4& a = skeletonRootWorld;
    for (int c = 0; c < 3; ++c) {
        const double b0 = model.linear[c][0], b1 = model.linear[c][1], b2 = model.linear[c][2];
        for (int row = 0; row < 3; ++row) world.linear[c][row] = static_cast<float>(a[0][row] * b0 + a[1][row] * b1 + a[2][row] * b2);
    }
    const double t0 = model.translation[0], t1 = model.translation[1], t2 = model.translation[2];
    for (int row = 0; row < 3; ++row) world.translation[row] = a[0][row] * t0 + a[1][row] * t1 + a[2][row] * t2 + a[3][row];
    THRONG_TALLY(ops, 36, 27, 0, 0);
}

/// World sphere of a part (see throng::partWorldSphere).
template <class S>
BasicBoundingSphere<Wide<S>> partWorldSphere(const BasicBoundingSphere<Wide<S>>& local, const BasicAffine<S>& model,
                                             const glm::mat<4, 4, Wide<S>, glm::defaultp>& skeletonRootWorld,
                                             OpTally* ops) {
    return local.transformed(model.toDMat4(), ops).transformed(skeletonRootWorld, ops);
}

/// Local transform of `node` from its DOF values (see throng::nodeLocalTransform).
template <class S>
BasicAffine<S> nodeLocalTransform(const SkeletonNode& node, const S* v, OpTally* ops) {
    using V = glm::vec<3, S, glm::defaultp>;
    using Q = glm::qua<S, glm::defaultp>;
    V t = convertTo<V>(node.restTranslation);
    Q r = convertTo<Q>(node.restRotation);
    V s = convertTo<V>(node.restScale);
    for (const Dof& d : node.dofs) {
        switch (d.kind) {
            case DofKind::RotateAxis: {
                const S angle = std::clamp(v[0], S(d.min), S(d.max));
                const S half = S(0.5f) * angle;
                const S sn = sinOf(half);
                r = r * Q(cosOf(half), convertTo<V>(d.axis) * sn);
                THRONG_TALLY(ops, 20, 14, 0, 2);  // clamp, half angle, sin+cos, axis, quaternion product
                break;
            }
            case DofKind::TranslateAxis:
                t += convertTo<V>(d.axis) * std::clamp(v[0], S(d.min), S(d.max));
                THRONG_TALLY(ops, 3, 5, 0, 0);
                break;
            case DofKind::Orientation:
                r = r * Q(v[3], v[0], v[1], v[2]);
                THRONG_TALLY(ops, 16, 12, 0, 0);
                break;
            case DofKind::Position:
                t += V(v[0], v[1], v[2]);
                THRONG_TALLY(ops, 0, 3, 0, 0);
                break;
            case DofKind::Scale:
                s *= V(v[0], v[1], v[2]);
                THRONG_TALLY(ops, 3, 0, 0, 0);
                break;
        }
        v += dofValueCount(d.kind);
    }
    // Rotation to matrix, columns scaled (18 mults, 15 adds, as matrixFromDofs).
    const S x2 = r.x + r.x, y2 = r.y + r.y, z2 = r.z + r.z;
    const S xx = r.x * x2, xy = r.x * y2, xz = r.x * z2, yy = r.y * y2, yz = r.y * z2, zz = r.z * z2;
    const S wx = r.w * x2, wy = r.w * y2, wz = r.w * z2;
    BasicAffine<S> a;
    a.linear[0] = V(S(1) - (yy + zz), xy + wz, xz - wy) * s.x;
    a.linear[1] = V(xy - wz, S(1) - (xx + zz), yz + wx) * s.y;
    a.linear[2] = V(xz + wy, yz - wx, S(1) - (xx + yy)) * s.z;
    a.translation = t;
    THRONG_TALLY(ops, 18, 15, 0, 0);
    return a;
}

/// Model transforms of the active nodes (see throng::computeModelTransforms).
template <class S>
std::size_t computeModelTransforms(const ActorTemplate& tmpl, std::span<const S> dofs, std::span<const std::uint8_t> active,
                                   std::span<BasicAffine<S>> model, OpTally* ops) {
    const auto nodes = tmpl.nodes();
    std::size_t count = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (!active.empty() && !active[i]) {
            i = tmpl.subtreeEnd(i) - 1;  // an inactive node's subtree is not traversed
            continue;
        }
        const BasicAffine<S> local = nodeLocalTransform(nodes[i], dofs.data() + tmpl.dofOffset(i), ops);
        const int p = nodes[i].parent;
        model[i] = p < 0 ? local : compose(model[static_cast<std::size_t>(p)], local, ops);
        ++count;
    }
    return count;
}

/// Internal bounding spheres of the active nodes (see throng::computeInternalSpheres).
template <class S>
BasicBoundingSphere<Wide<S>> computeInternalSpheres(const ActorTemplate& tmpl, std::span<const BasicAffine<S>> model,
                                                    std::span<const std::uint8_t> active,
                                                    std::span<BasicBoundingSphere<Wide<S>>> geometry,
                                                    std::span<BasicBoundingSphere<Wide<S>>> subtree, OpTally* ops) {
    using Sphere = BasicBoundingSphere<Wide<S>>;
    const auto nodes = tmpl.nodes();
    const std::size_t n = nodes.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (!active.empty() && !active[i]) {
            i = tmpl.subtreeEnd(i) - 1;
            continue;
        }
        const Sphere& local = convertTo<Sphere>(nodes[i].geometrySphere);
        THRONG_TALLY(ops, 0, 1, 0, 0);  // the emptiness test
        geometry[i] = local.valid() ? local.transformed(model[i].toDMat4(), ops) : Sphere();
        subtree[i] = geometry[i];
    }
    // Children come after their parents, so walking backwards completes each subtree before its parent.
    Sphere whole = convertTo<Sphere>(tmpl.rootGeometry().bound());
    for (std::size_t i = n; i-- > 0;) {
        if (!active.empty() && !active[i]) continue;
        const int p = nodes[i].parent;
        if (p >= 0) subtree[static_cast<std::size_t>(p)].expandBy(subtree[i], ops);
        else whole.expandBy(subtree[i], ops);
    }
    return whole;
}

}  // namespace throng::detail
