#include "throng/actors/SeedHumanoid.h"

#include <cmath>
#include <numbers>
#include <string>

#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"

namespace throng {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
const glm::vec4 kSkin(0.85f, 0.68f, 0.55f, 1.0f), kCloth(0.25f, 0.35f, 0.6f, 1.0f), kTrousers(0.3f, 0.3f, 0.32f, 1.0f);

std::shared_ptr<const Drawable> drawable(std::shared_ptr<MeshData> mesh) {
    return std::make_shared<MeshDrawable>(std::move(mesh));
}

// Tessellation (segments, rings) of rigid segments at levels 0..3.
constexpr int kSegments[4] = {16, 10, 7, 5};
constexpr int kRings[4] = {4, 3, 2, 1};

std::shared_ptr<const Drawable> limb(const std::string& name, float radius, float length, int level, const glm::vec4& color) {
    // Limbs hang down -Y from their joint.
    return drawable(makeCapsule(name + "_L" + std::to_string(level), glm::vec3(0, -length - 2 * radius, 0), radius, length,
                                kSegments[level], kRings[level], color));
}

ClipChannel rotation(std::uint32_t node, std::uint32_t dof, std::vector<float> times, std::vector<float> angles) {
    ClipChannel c;
    c.node = node;
    c.dof = dof;
    c.times = std::move(times);
    c.values = std::move(angles);
    return c;
}

}  // namespace

std::shared_ptr<const ActorTemplate> makeSeedHumanoid(const SeedHumanoidLods& l) {
    ActorTemplateBuilder b("seed-humanoid");
    const glm::vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
    auto node = [&](std::string name, int parent, glm::vec3 offset, std::vector<Dof> dofs, double deactivation) {
        SkeletonNode n;
        n.name = std::move(name);
        n.parent = parent;
        n.restTranslation = offset;
        n.dofs = std::move(dofs);
        n.deactivationDistance = deactivation;
        return n;
    };

    // 0 pelvis: its geometry lasts until every node is deactivated.
    SkeletonNode pelvis = node("pelvis", -1, glm::vec3(0, 0.95f, 0), {}, l.limbs);
    for (int lv = 0; lv < 4; ++lv)
        pelvis.geometry.addLevel(lv == 0 ? l.eyes : lv == 1 ? l.head : lv == 2 ? l.forearms : l.limbs,
                                 drawable(makeCapsule("pelvis_L" + std::to_string(lv), glm::vec3(0, -0.12f, 0), 0.16f, 0.05f,
                                                      kSegments[lv], kRings[lv], kTrousers)));
    const int iPelvis = b.addNode(std::move(pelvis));
    // 1 spine (torso); from level 2 its geometry includes the head.
    SkeletonNode spine = node("spine", iPelvis, glm::vec3(0, 0.1f, 0),
                              {Dof::rotation(X, -0.3f, 0.5f), Dof::rotation(Y, -0.6f, 0.6f)}, l.limbs);
    for (int lv = 0; lv < 4; ++lv) {
        auto torso = makeCapsule("torso_L" + std::to_string(lv), glm::vec3(0, 0.0f, 0), 0.18f, 0.3f, kSegments[lv], kRings[lv], kCloth);
        if (lv >= 2) {
            auto head = makeSphere("head", glm::vec3(0, 0.78f, 0.02f), 0.11f, kSegments[lv], kRings[lv] + 2, kSkin);
            torso = mergeMeshes("torso_head_L" + std::to_string(lv), *torso, *head);
        }
        spine.geometry.addLevel(lv == 0 ? l.eyes : lv == 1 ? l.head : lv == 2 ? l.forearms : l.limbs, drawable(torso));
    }
    const int iSpine = b.addNode(std::move(spine));
    // 2 neck, 3 head, 4 eyes.
    SkeletonNode neck = node("neck", iSpine, glm::vec3(0, 0.62f, 0), {Dof::rotation(X, -0.5f, 0.5f), Dof::rotation(Y, -1.2f, 1.2f)}, l.head);
    neck.geometry.addLevel(l.eyes, drawable(makeCapsule("neck_L0", glm::vec3(0), 0.05f, 0.04f, kSegments[0], kRings[0], kSkin)));
    neck.geometry.addLevel(l.head, drawable(makeCapsule("neck_L1", glm::vec3(0), 0.05f, 0.04f, kSegments[1], kRings[1], kSkin)));
    const int iNeck = b.addNode(std::move(neck));
    SkeletonNode head = node("head", iNeck, glm::vec3(0, 0.12f, 0), {Dof::rotation(Z, -0.4f, 0.4f)}, l.head);
    head.geometry.addLevel(l.eyes, drawable(makeSphere("head_L0", glm::vec3(0, 0.1f, 0.02f), 0.11f, 20, 14, kSkin)));
    head.geometry.addLevel(l.head, drawable(makeSphere("head_L1", glm::vec3(0, 0.1f, 0.02f), 0.11f, 12, 8, kSkin)));
    const int iHead = b.addNode(std::move(head));
    SkeletonNode eyes = node("eyes", iHead, glm::vec3(0, 0.12f, 0.1f), {Dof::rotation(Y, -0.7f, 0.7f), Dof::rotation(X, -0.4f, 0.4f)}, l.eyes);
    auto left = makeSphere("eye", glm::vec3(0.035f, 0, 0), 0.018f, 8, 6, glm::vec4(1));
    auto right = makeSphere("eye", glm::vec3(-0.035f, 0, 0), 0.018f, 8, 6, glm::vec4(1));
    eyes.geometry.addLevel(l.eyes, drawable(mergeMeshes("eyes_L0", *left, *right)));
    b.addNode(std::move(eyes));
    // 5-8 arms: upper arm shows the whole arm at level 3.
    for (int side = 0; side < 2; ++side) {
        const std::string s = side == 0 ? "l" : "r";
        const float x = side == 0 ? 0.22f : -0.22f;
        SkeletonNode shoulder = node(s + "Shoulder", iSpine, glm::vec3(x, 0.5f, 0),
                                     {Dof::rotation(X, -1.5f, 1.0f), Dof::rotation(Z, side == 0 ? 0.0f : -1.5f, side == 0 ? 1.5f : 0.0f)}, l.limbs);
        shoulder.geometry.addLevel(l.eyes, limb(s + "UpperArm", 0.05f, 0.2f, 0, kCloth));
        shoulder.geometry.addLevel(l.head, limb(s + "UpperArm", 0.05f, 0.2f, 1, kCloth));
        shoulder.geometry.addLevel(l.forearms, limb(s + "UpperArm", 0.05f, 0.2f, 2, kCloth));
        shoulder.geometry.addLevel(l.limbs, limb(s + "Arm", 0.05f, 0.5f, 3, kCloth));
        const int iShoulder = b.addNode(std::move(shoulder));
        SkeletonNode elbow = node(s + "Elbow", iShoulder, glm::vec3(0, -0.3f, 0), {Dof::rotation(X, -2.5f, 0.0f)}, l.forearms);
        for (int lv = 0; lv < 3; ++lv)
            elbow.geometry.addLevel(lv == 0 ? l.eyes : lv == 1 ? l.head : l.forearms, limb(s + "Forearm", 0.04f, 0.2f, lv, kSkin));
        b.addNode(std::move(elbow));
    }
    // 9-12 legs.
    for (int side = 0; side < 2; ++side) {
        const std::string s = side == 0 ? "l" : "r";
        const float x = side == 0 ? 0.1f : -0.1f;
        SkeletonNode hip = node(s + "Hip", iPelvis, glm::vec3(x, -0.05f, 0),
                                {Dof::rotation(X, -1.2f, 0.8f), Dof::rotation(Z, side == 0 ? -0.3f : -0.5f, side == 0 ? 0.5f : 0.3f)}, l.limbs);
        hip.geometry.addLevel(l.eyes, limb(s + "Thigh", 0.07f, 0.28f, 0, kTrousers));
        hip.geometry.addLevel(l.head, limb(s + "Thigh", 0.07f, 0.28f, 1, kTrousers));
        hip.geometry.addLevel(l.forearms, limb(s + "Thigh", 0.07f, 0.28f, 2, kTrousers));
        hip.geometry.addLevel(l.limbs, limb(s + "Leg", 0.07f, 0.76f, 3, kTrousers));
        const int iHip = b.addNode(std::move(hip));
        SkeletonNode knee = node(s + "Knee", iHip, glm::vec3(0, -0.42f, 0), {Dof::rotation(X, 0.0f, 2.2f)}, l.forearms);
        for (int lv = 0; lv < 3; ++lv)
            knee.geometry.addLevel(lv == 0 ? l.eyes : lv == 1 ? l.head : l.forearms, limb(s + "Shin", 0.055f, 0.32f, lv, kTrousers));
        b.addNode(std::move(knee));
    }
    // Level 4: one piece for the whole figure at the actor level.
    b.rootGeometry().addLevel(l.limbs, nullptr);
    auto body = makeBox("figure_L4", glm::vec3(0, 0.9f, 0), glm::vec3(0.22f, 0.9f, 0.12f), kCloth);
    b.rootGeometry().addLevel(l.figure, drawable(body));

    // "walk": a 2 s key-framing table, keys every 0.25 s.
    std::vector<float> times;
    for (int k = 0; k <= 8; ++k) times.push_back(0.25f * float(k));
    auto swing = [&](float amplitude, float phase, float offset) {
        std::vector<float> v;
        for (float t : times) v.push_back(offset + amplitude * std::sin(kPi * t + phase));
        return v;
    };
    std::vector<ClipChannel> walk = {
        rotation(1, 1, times, swing(0.15f, 0.0f, 0.0f)),            // spine twist
        rotation(5, 0, times, swing(0.5f, kPi, 0.0f)),              // left shoulder swing
        rotation(6, 0, times, swing(0.4f, kPi, -0.5f)),             // left elbow
        rotation(7, 0, times, swing(0.5f, 0.0f, 0.0f)),             // right shoulder
        rotation(8, 0, times, swing(0.4f, 0.0f, -0.5f)),            // right elbow
        rotation(9, 0, times, swing(0.55f, 0.0f, -0.1f)),           // left hip
        rotation(10, 0, times, swing(0.6f, 0.5f * kPi, 0.6f)),      // left knee
        rotation(11, 0, times, swing(0.55f, kPi, -0.1f)),           // right hip
        rotation(12, 0, times, swing(0.6f, 1.5f * kPi, 0.6f)),      // right knee
        rotation(2, 1, times, swing(0.3f, 0.25f * kPi, 0.0f)),      // neck looks around
        rotation(4, 0, times, swing(0.5f, 0.5f * kPi, 0.0f)),       // eyes
    };
    ClipChannel bob;
    bob.target = ClipChannel::Target::RootTranslation;
    bob.times = times;
    for (float t : times) bob.values.insert(bob.values.end(), {0.0f, 0.03f * std::sin(2.0f * kPi * t) * std::sin(2.0f * kPi * t), 0.0f});
    walk.push_back(bob);
    b.addClip(std::make_shared<AnimationClip>("walk", std::move(walk)));

    // "pirouette": the Skeleton Root travels a 1 m circle round the Reference Point while turning.
    ClipChannel around;
    around.target = ClipChannel::Target::RootTranslation;
    ClipChannel turn;
    turn.target = ClipChannel::Target::RootOrientation;
    for (int k = 0; k <= 16; ++k) {
        const float t = 0.25f * float(k), a = 2.0f * kPi * float(k) / 16.0f;
        around.times.push_back(t);
        around.values.insert(around.values.end(), {std::cos(a), 0.0f, std::sin(a)});
        turn.times.push_back(t);
        const glm::quat q = glm::angleAxis(-2.0f * a, glm::vec3(0, 1, 0));
        turn.values.insert(turn.values.end(), {q.x, q.y, q.z, q.w});
    }
    b.addClip(std::make_shared<AnimationClip>("pirouette",
                                              std::vector<ClipChannel>{around, turn, rotation(5, 1, {0.0f, 4.0f}, {1.2f, 1.2f}),
                                                                       rotation(7, 1, {0.0f, 4.0f}, {-1.2f, -1.2f})}));
    return b.build();
}

}  // namespace throng
