#include "throng/actors/SkeletonPose.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

#include "throng/scenegraph/Transform.h"

namespace throng {

std::size_t computeActiveNodes(const ActorTemplate& tmpl, double distance2, std::span<std::uint8_t> active) {
    const auto nodes = tmpl.nodes();
    std::size_t count = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const int p = nodes[i].parent;
        const bool parentActive = p < 0 || active[static_cast<std::size_t>(p)];
        const double d = nodes[i].deactivationDistance;
        const bool on = parentActive && distance2 < d * d;
        active[i] = on ? 1 : 0;
        count += on;
    }
    return count;
}

void computeSkinPalette(const ActorTemplate& tmpl, const Skin& skin, std::span<const Affine> model,
                        std::span<const std::uint8_t> active, std::span<glm::mat4> palette, OpTally* ops) {
    const auto nodes = tmpl.nodes();
    for (std::size_t k = 0; k < skin.joints.size(); ++k) {
        int n = static_cast<int>(skin.joints[k]);
        while (n >= 0 && !active.empty() && !active[static_cast<std::size_t>(n)]) n = nodes[static_cast<std::size_t>(n)].parent;
        if (n < 0) {
            palette[k] = glm::mat4(1.0f);
            continue;
        }
        const auto node = static_cast<std::size_t>(n);
        palette[k] = model[node].toMat4() * nodes[node].inverseBind;
        THRONG_TALLY(ops, 64, 48, 0, 0);
    }
}

double detailDistanceSquared(const Mat4& skeletonRootWorld, const Vec3& eye, double lodScale2, float priority,
                             OpTally* ops) {
    const Vec3 d = Vec3(skeletonRootWorld[3]) - eye;
    const double p = static_cast<double>(priority);
    THRONG_TALLY(ops, 5, 5, 1, 0);  // the distance (8 FMULT), then the scale and the priority
    return glm::dot(d, d) * lodScale2 / (p * p);
}

Mat4 rootPoseMatrix(const RootPose& root, OpTally* ops) {
    TransformDofs dofs;
    dofs.translation = Vec3(root.translation);
    dofs.rotation = Quat(root.orientation);
    return matrixFromDofs(dofs, ops);
}

BoundingSphere partWorldSphere(const BoundingSphere& local, const Affine& model, const Mat4& skeletonRootWorld,
                               OpTally* ops) {
    return local.transformed(model.toDMat4(), ops).transformed(skeletonRootWorld, ops);
}

void writeRestPose(const ActorTemplate& tmpl, std::span<const std::uint8_t> active, std::span<float> dofs) {
    const auto rest = tmpl.restDofs();
    for (std::size_t i = 0; i < tmpl.nodeCount(); ++i) {
        if (!active.empty() && !active[i]) continue;
        const std::uint32_t begin = tmpl.dofOffset(i);
        const std::uint32_t end = i + 1 < tmpl.nodeCount() ? tmpl.dofOffset(i + 1) : tmpl.dofValueCount();
        std::copy(rest.begin() + begin, rest.begin() + end, dofs.begin() + begin);
    }
}

Affine nodeLocalTransform(const SkeletonNode& node, const float* v, OpTally* ops) {
    glm::vec3 t = node.restTranslation;
    glm::quat r = node.restRotation;
    glm::vec3 s = node.restScale;
    for (const Dof& d : node.dofs) {
        switch (d.kind) {
            case DofKind::RotateAxis: {
                const float angle = std::clamp(v[0], d.min, d.max);
                const float half = 0.5f * angle;
                const float sn = std::sin(half);
                r = r * glm::quat(std::cos(half), d.axis * sn);
                THRONG_TALLY(ops, 20, 14, 0, 2);  // clamp, half angle, sin+cos, axis, quaternion product
                break;
            }
            case DofKind::TranslateAxis:
                t += d.axis * std::clamp(v[0], d.min, d.max);
                THRONG_TALLY(ops, 3, 5, 0, 0);
                break;
            case DofKind::Orientation:
                r = r * glm::quat(v[3], v[0], v[1], v[2]);
                THRONG_TALLY(ops, 16, 12, 0, 0);
                break;
            case DofKind::Position:
                t += glm::vec3(v[0], v[1], v[2]);
                THRONG_TALLY(ops, 0, 3, 0, 0);
                break;
            case DofKind::Scale:
                s *= glm::vec3(v[0], v[1], v[2]);
                THRONG_TALLY(ops, 3, 0, 0, 0);
                break;
        }
        v += dofValueCount(d.kind);
    }
    // Rotation to matrix, columns scaled (18 mults, 15 adds, as matrixFromDofs).
    const float x2 = r.x + r.x, y2 = r.y + r.y, z2 = r.z + r.z;
    const float xx = r.x * x2, xy = r.x * y2, xz = r.x * z2, yy = r.y * y2, yz = r.y * z2, zz = r.z * z2;
    const float wx = r.w * x2, wy = r.w * y2, wz = r.w * z2;
    Affine a;
    a.linear[0] = glm::vec3(1.0f - (yy + zz), xy + wz, xz - wy) * s.x;
    a.linear[1] = glm::vec3(xy - wz, 1.0f - (xx + zz), yz + wx) * s.y;
    a.linear[2] = glm::vec3(xz + wy, yz - wx, 1.0f - (xx + yy)) * s.z;
    a.translation = t;
    THRONG_TALLY(ops, 18, 15, 0, 0);
    return a;
}

std::size_t computeModelTransforms(const ActorTemplate& tmpl, std::span<const float> dofs,
                                   std::span<const std::uint8_t> active, std::span<Affine> model, OpTally* ops) {
    const auto nodes = tmpl.nodes();
    std::size_t count = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (!active.empty() && !active[i]) {
            i = tmpl.subtreeEnd(i) - 1;  // an inactive node's subtree is not traversed
            continue;
        }
        const Affine local = nodeLocalTransform(nodes[i], dofs.data() + tmpl.dofOffset(i), ops);
        const int p = nodes[i].parent;
        model[i] = p < 0 ? local : compose(model[static_cast<std::size_t>(p)], local, ops);
        ++count;
    }
    return count;
}

BoundingSphere computeInternalSpheres(const ActorTemplate& tmpl, std::span<const Affine> model,
                                      std::span<const std::uint8_t> active, std::span<BoundingSphere> geometry,
                                      std::span<BoundingSphere> subtree, OpTally* ops) {
    const auto nodes = tmpl.nodes();
    const std::size_t n = nodes.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (!active.empty() && !active[i]) {
            i = tmpl.subtreeEnd(i) - 1;
            continue;
        }
        geometry[i] = nodes[i].geometrySphere.valid() ? nodes[i].geometrySphere.transformed(model[i].toDMat4(), ops)
                                                       : BoundingSphere();
        subtree[i] = geometry[i];
    }
    // Children come after their parents, so walking backwards completes each subtree before its parent.
    BoundingSphere whole = tmpl.rootGeometry().bound();
    for (std::size_t i = n; i-- > 0;) {
        if (!active.empty() && !active[i]) continue;
        const int p = nodes[i].parent;
        if (p >= 0) subtree[static_cast<std::size_t>(p)].expandBy(subtree[i], ops);
        else whole.expandBy(subtree[i], ops);
    }
    return whole;
}

}  // namespace throng
