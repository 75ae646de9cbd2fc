#pragma once
// Random crowds and draw-list comparison shared by the actor, VTK and cascade tests (header only).

#include <algorithm>
#include <numbers>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "throng/actors/Actor.h"
#include "throng/actors/ActorFrameStatistics.h"
#include "throng/actors/ActorGroup.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/ProceduralGait.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/actors/Table3Template.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/Transform.h"

namespace throng::testkit {

/// A primitive's identity: node, instance, part, drawable.
using PrimitiveKey = std::tuple<const void*, std::uint32_t, std::uint32_t, const void*>;

/// The draw list as a sorted list of primitive identities.
inline std::vector<PrimitiveKey> primitives(const DrawList& list) {
    std::vector<PrimitiveKey> keys;
    for (const DrawItem& i : list.items()) keys.emplace_back(i.node, i.instance, i.part, i.drawable);
    std::sort(keys.begin(), keys.end());
    return keys;
}

/// A random crowd: humanoids and Table 3 actors, key-framed or walking procedurally, some alone,
/// some in groups, some under a moving generic Transform (a vehicle), spread over a square.
struct RandomCrowd {
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::shared_ptr<Transform> vehicle = std::make_shared<Transform>();
    std::vector<ActorId> ids;
};

/// `deferState`: the crowd defers its actors' per-frame state until shown (Crowd::deferStateUntilShown).
inline std::unique_ptr<RandomCrowd> makeRandomCrowd(std::uint64_t seed, int actors, double extent, bool deferState = false) {
    auto scene = std::make_unique<RandomCrowd>();
    if (deferState) scene->crowd.deferStateUntilShown();
    static const auto humanoid = makeSeedHumanoid();
    static const auto table3 = makeTable3Template();
    auto keyframes = std::make_shared<KeyframeBehaviour>(std::vector<double>{30.0, 1e9});
    auto gait = std::make_shared<ProceduralGait>(std::vector<double>{25.0, 1e9});
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
    std::vector<ActorId> grouped, onVehicle;
    for (int i = 0; i < actors; ++i) {
        const auto tmpl = unit(rng) < 0.5 ? humanoid : table3;
        const Vec3 where(extent * u(rng), 0.2 * extent * u(rng), extent * u(rng));
        ActorId id;
        if (unit(rng) < 0.6) {
            KeyframeBehaviour::Actor a;
            a.tmpl = tmpl;
            a.clip = static_cast<int>(unit(rng) * double(tmpl->clips().size()));
            a.timeOffset = 10.0 * unit(rng);
            a.position = where;
            a.heading = 6.3 * unit(rng);
            a.pathRadius = unit(rng) < 0.3 ? 4.0 : 0.0;
            a.pathSpeed = 1.4;
            id = scene->crowd.add(tmpl, keyframes, keyframes->addActor(a), ActorLook{float(0.5 + unit(rng)), glm::vec4(1), {}});
        } else {
            ProceduralGait::Actor a;
            a.center = where;
            a.radius = 6.0 * unit(rng);
            a.phase = 6.3 * unit(rng);
            id = scene->crowd.add(tmpl, gait, gait->addActor(a));
        }
        scene->ids.push_back(id);
        const double r = unit(rng);
        if (r < 0.45) scene->root->addChild(scene->crowd.makeActorNode(id));
        else if (r < 0.9) grouped.push_back(id);
        else onVehicle.push_back(id);
    }
    for (std::size_t g = 0; g < grouped.size(); g += 50)
        scene->root->addChild(scene->crowd.makeGroupNode(
            std::vector<ActorId>(grouped.begin() + long(g), grouped.begin() + long(std::min(g + 50, grouped.size())))));
    scene->vehicle->setName("vehicle");
    for (ActorId id : onVehicle) scene->vehicle->addChild(scene->crowd.makeActorNode(id));
    scene->root->addChild(scene->vehicle);
    return scene;
}

// A 2 m bar skinned to two joints: "base" at the origin and "arm" 1 m up, which turns about Z
// (switched off beyond `armOff` metres); no clip yet.
inline ActorTemplateBuilder skinnedBarBuilder(const std::string& name, double armOff = 20.0) {
    SkeletonNode base;
    base.name = "base";
    SkeletonNode arm;
    arm.name = "arm";
    arm.parent = 0;
    arm.restTranslation = glm::vec3(0, 1, 0);
    arm.dofs = {Dof::rotation(glm::vec3(0, 0, 1), -3.2f, 3.2f)};
    arm.deactivationDistance = armOff;
    arm.inverseBind = glm::mat4(1.0f);
    arm.inverseBind[3] = glm::vec4(0, -1, 0, 1);  // inverse of the bind pose's translation
    auto mesh = makeBox("bar", glm::vec3(0, 1, 0), glm::vec3(0.05f, 1.0f, 0.05f));
    for (const glm::vec3& p : mesh->positions) {
        mesh->joints0.push_back(glm::u16vec4(p.y < 1.0f ? 0 : 1, 0, 0, 0));
        mesh->weights0.push_back(glm::vec4(1, 0, 0, 0));
    }
    // Joint spheres from the vertices each dominates, in the joint's frame.
    base.geometrySphere = BoundingSphere(Vec3(0, 0.5, 0), 0.6);
    arm.geometrySphere = BoundingSphere(Vec3(0, 0.5, 0), 0.6);
    ActorTemplateBuilder b(name);
    b.addNode(base);
    b.addNode(arm);
    const int skin = b.addSkin(Skin{"bar", {0, 1}});
    b.rootGeometry().addLevel(1000.0, std::make_shared<MeshDrawable>(mesh), skin);
    return b;
}

// The bar's clip "bend" (2 s): the arm turns to 90 degrees over the first second and holds.
inline std::shared_ptr<const AnimationClip> barBendClip() {
    ClipChannel bend;
    bend.node = 1;
    bend.times = {0.0f, 1.0f, 2.0f};
    bend.values = {0.0f, std::numbers::pi_v<float> / 2.0f, std::numbers::pi_v<float> / 2.0f};
    return std::make_shared<AnimationClip>("bend", std::vector<ClipChannel>{bend});
}

// The skinned bar playing "bend".
inline std::shared_ptr<const ActorTemplate> skinnedBar() {
    ActorTemplateBuilder b = skinnedBarBuilder("bar");
    b.addClip(barBendClip());
    return b.build();
}

/// Key-framed actors of which this process holds those marked in `here` (per slot; empty: every
/// one), as a rank holds its share of a crowd (Behaviour::presence), each stepped in the region
/// `region` gives it (empty: no regions).
class KeyframeShare : public KeyframeBehaviour {
public:
    std::vector<std::uint8_t> here;     ///< per slot, 1 when held here
    std::vector<std::uint32_t> region;  ///< per slot, the region stepping it
    bool presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const override {
        if (here.empty()) return true;
        for (std::size_t k = 0; k < slots.size(); ++k) present[k] = here[slots[k]];
        return false;
    }
    bool steppingRegions(std::span<const std::uint32_t> slots, std::span<std::uint32_t> regions) const override {
        if (region.empty()) return false;
        for (std::size_t k = 0; k < slots.size(); ++k) regions[k] = region[slots[k]];
        return true;
    }
};

/// `count` actors of `tmpl` (skinned bars: skinnedBar) on a grid in front of the origin along +Z
/// (16 a row, 1.5 m apart, from 4 m), each at its own clip time, driven by `behaviour`, in one
/// group of `crowd`.
inline std::shared_ptr<ActorGroup> barGrid(Crowd& crowd, const std::shared_ptr<KeyframeBehaviour>& behaviour,
                                           const std::shared_ptr<const ActorTemplate>& tmpl, int count) {
    std::vector<ActorId> ids;
    for (int i = 0; i < count; ++i) {
        KeyframeBehaviour::Actor a;
        a.tmpl = tmpl;
        a.position = Vec3(1.5 * (i % 16) - 12.0, 0.0, 4.0 + 1.5 * (i / 16));
        a.timeOffset = 0.037 * ((i * 7) % 53);
        ids.push_back(crowd.add(tmpl, behaviour, behaviour->addActor(a)));
    }
    return crowd.makeGroupNode(ids);
}

/// Adds to `crowd` an actor of `tmpl` playing its keyframes through `behaviour`; returns its id.
inline ActorId addKeyframed(Crowd& crowd, const std::shared_ptr<const ActorTemplate>& tmpl, const std::shared_ptr<KeyframeBehaviour>& behaviour) {
    KeyframeBehaviour::Actor a;
    a.tmpl = tmpl;
    return crowd.add(tmpl, behaviour, behaviour->addActor(a));
}

/// A frame's actors per cascade class, "A B C1 C2 C3_1 C3_2", so a test states them in one line
/// and a failure shows them all.
inline std::string classCounts(const ActorFrameStatistics& s) {
    return std::to_string(s.a) + " " + std::to_string(s.b) + " " + std::to_string(s.c1) + " " + std::to_string(s.c2) + " " +
           std::to_string(s.c3_1) + " " + std::to_string(s.c3_2);
}

}  // namespace throng::testkit
