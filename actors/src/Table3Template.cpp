#include "throng/actors/Table3Template.h"

#include <cmath>
#include <numbers>
#include <string>

#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"

namespace throng {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr int kSpineNodes = 4, kLimbNodes = 9, kProximal = 4;  // 4 + 4 * 9 = 40 nodes

std::shared_ptr<const Drawable> capsule(const std::string& name, float length, int segments) {
    return std::make_shared<MeshDrawable>(makeCapsule(name, glm::vec3(0, -length - 0.08f, 0), 0.04f, length, segments, 1,
                                                      glm::vec4(0.7f, 0.6f, 0.4f, 1.0f)));
}

std::shared_ptr<const Drawable> box(const std::string& name, float length) {
    return std::make_shared<MeshDrawable>(makeBox(name, glm::vec3(0, -0.5f * length, 0), glm::vec3(0.04f, 0.5f * length, 0.04f),
                                                  glm::vec4(0.7f, 0.6f, 0.4f, 1.0f)));
}

}  // namespace

std::shared_ptr<const ActorTemplate> makeTable3Template(const Table3Options& o) {
    ActorTemplateBuilder b("table3-actor");
    const double nearEnd = 0.5 * o.halfDistance;
    auto addSegment = [&](const std::string& name, int parent, glm::vec3 offset, float length, bool distal, bool lastProximal) {
        SkeletonNode n;
        n.name = name;
        n.parent = parent;
        n.restTranslation = offset;
        n.dofs = {Dof::rotation(glm::vec3(1, 0, 0), -0.8f, 0.8f), Dof::rotation(glm::vec3(0, 0, 1), -0.8f, 0.8f)};
        n.geometry.addLevel(nearEnd, capsule(name + "_L0", length, 8));
        n.geometry.addLevel(o.halfDistance, box(name + "_L1", length));
        if (distal) {
            n.deactivationDistance = o.halfDistance;
        } else {
            // The last proximal node stands for the whole rest of its limb once the distal nodes are off.
            const float far = lastProximal ? length * float(kLimbNodes - kProximal + 1) : length;
            n.geometry.addLevel(o.farDistance, box(name + "_L2", far));
            n.deactivationDistance = o.farDistance;
        }
        return b.addNode(std::move(n));
    };
    int parent = -1;
    std::vector<int> spine;
    for (int i = 0; i < kSpineNodes; ++i) {
        parent = addSegment("spine" + std::to_string(i), parent, glm::vec3(0, i == 0 ? 1.0f : 0.2f, 0), 0.18f, false, false);
        spine.push_back(parent);
    }
    const char* limbs[4] = {"lArm", "rArm", "lLeg", "rLeg"};
    for (int limb = 0; limb < 4; ++limb) {
        const bool arm = limb < 2;
        const float side = limb % 2 == 0 ? 1.0f : -1.0f;
        parent = arm ? spine.back() : spine.front();
        for (int k = 0; k < kLimbNodes; ++k) {
            const glm::vec3 offset = k == 0 ? glm::vec3(side * 0.2f, arm ? 0.1f : -0.1f, 0) : glm::vec3(0, -0.1f, 0);
            parent = addSegment(std::string(limbs[limb]) + std::to_string(k), parent, offset, 0.08f, k >= kProximal,
                                k == kProximal - 1);
        }
    }
    // The actor's own LOD node: nothing while Skeleton nodes show geometry, then one piece.
    b.rootGeometry().addLevel(o.farDistance, nullptr);
    b.rootGeometry().addLevel(5.0 * o.farDistance, std::make_shared<MeshDrawable>(makeBox(
                                                       "figure", glm::vec3(0, 0.9f, 0), glm::vec3(0.3f, 0.9f, 0.15f))));

    // "sway": every DOF swings (keys every 0.5 s over 4 s); the Skeleton Root circles the Reference Point.
    std::vector<ClipChannel> channels;
    for (std::uint32_t node = 0; node < 40; ++node)
        for (std::uint32_t dof = 0; dof < 2; ++dof) {
            ClipChannel c;
            c.node = node;
            c.dof = dof;
            for (int k = 0; k <= 8; ++k) {
                c.times.push_back(0.5f * float(k));
                c.values.push_back(0.3f * std::sin(0.25f * kPi * float(k) + 0.7f * float(node) + 1.3f * float(dof)));
            }
            channels.push_back(std::move(c));
        }
    ClipChannel root;
    root.target = ClipChannel::Target::RootTranslation;
    for (int k = 0; k <= 16; ++k) {
        const float a = 2.0f * kPi * float(k) / 16.0f;
        root.times.push_back(0.25f * float(k));
        root.values.insert(root.values.end(), {float(o.rootCircle) * std::cos(a), 0.0f, float(o.rootCircle) * std::sin(a)});
    }
    channels.push_back(std::move(root));
    b.addClip(std::make_shared<AnimationClip>("sway", std::move(channels)));
    return b.build();
}

}  // namespace throng
