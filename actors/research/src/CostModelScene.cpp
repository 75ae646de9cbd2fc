#include "throng/research/CostModelScene.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "throng/actors/Actor.h"
#include "throng/actors/ActorGroup.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/Table3Template.h"
#include "throng/scenegraph/Validation.h"

namespace throng {

CascadeCounts CascadeCounts::scaled(std::size_t actors) {
    // Largest remainders, so the total is exact.
    const double shares[6] = {0.2, 0.3, 0.2, 0.2, 0.08, 0.02};
    std::size_t n[6], sum = 0;
    double rest[6];
    for (int i = 0; i < 6; ++i) {
        const double x = shares[i] * double(actors);
        n[i] = static_cast<std::size_t>(std::floor(x));
        rest[i] = x - double(n[i]);
        sum += n[i];
    }
    while (sum < actors) {
        const int i = static_cast<int>(std::max_element(rest, rest + 6) - rest);
        ++n[i];
        rest[i] = -1.0;
        ++sum;
    }
    return CascadeCounts{n[0], n[1], n[2], n[3], n[4], n[5]};
}

CostModelScene buildCostModelScene(Crowd& crowd, std::shared_ptr<const ActorTemplate> tmpl,
                                   std::shared_ptr<KeyframeBehaviour> behaviour, const CostModelSceneOptions& o) {
    if (!tmpl || !behaviour) throw std::invalid_argument("buildCostModelScene: template and behaviour are required");
    requireFinite(o.origin, "buildCostModelScene", "options.origin");
    if (!(o.nearDepth > 0.0) || !(o.farDepth > o.nearDepth))
        throw std::invalid_argument("buildCostModelScene: depths must satisfy 0 < nearDepth < farDepth");
    CostModelScene scene;
    scene.root = std::make_shared<Group>();
    scene.root->setName("costModelScene");
    // Eye at the origin, looking down -Z: the right plane of the frustum is vertical, so a heading
    // about +Y can turn any horizontal offset towards or away from it.
    const double fovY = std::numbers::pi / 3.0, aspect = 4.0 / 3.0;
    scene.camera.setPerspective(fovY, aspect, 0.5, 4.0 * o.farDepth);
    scene.camera.setLookAt(o.origin, o.origin + Vec3(0, 0, -1), Vec3(0, 1, 0));
    const Frustum frustum = scene.camera.frustum();
    const Vec3 n = Vec3(frustum.plane(Frustum::kRight));  // inward normal, horizontal
    const double tanH = aspect * std::tan(0.5 * fovY);
    const double t = scene.time;

    // What the template looks like at time t from the actors' point of view: the Skeleton Root
    // offset from the Reference Point (the clip's root channel) and the internal spheres with the
    // nodes active beyond the half-detail distance. t is a key time, so both behaviour levels agree.
    const AnimationClip& clip = *tmpl->clips()[0];
    const glm::vec3 offset = clip.sampleRoot(t, true).translation;
    const double offsetLength = glm::length(glm::dvec3(offset));
    std::vector<float> dofs(tmpl->restDofs().begin(), tmpl->restDofs().end());
    clip.sample(*tmpl, t, true, {}, dofs);
    std::vector<std::uint8_t> active(tmpl->nodeCount());
    computeActiveNodes(*tmpl, o.nearDepth * o.nearDepth, active);
    std::vector<Affine> model(tmpl->nodeCount());
    computeModelTransforms(*tmpl, dofs, active, model);
    std::vector<BoundingSphere> geometry(tmpl->nodeCount()), subtree(tmpl->nodeCount());
    const BoundingSphere whole = computeInternalSpheres(*tmpl, model, active, geometry, subtree);

    // The Refpoint Bsphere (Reference Point frame) the behaviour will give these actors.
    KeyframeBehaviour probe;
    KeyframeBehaviour::Actor probeActor;
    probeActor.tmpl = tmpl;
    const BoundingSphere extent = probe.skeletonRootExtent(probe.addActor(probeActor));
    const Vec3 extentCentre = extent.center();
    const double rRef = extent.radius() + tmpl->skeletonRootRadius();
    const Vec3 along = glm::normalize(glm::cross(n, Vec3(0, 1, 0)));  // horizontal, in the right plane

    std::mt19937_64 rng(o.seed);
    std::uniform_real_distribution<double> depthOf(o.nearDepth, o.farDepth), unit(0.0, 1.0);
    auto heading = [&](const Vec3& dir) { return std::atan2(dir.x, dir.z) - 0.5 * std::numbers::pi; };  // turns +X to `dir`
    auto place = [&](int cls, std::size_t count) {
        for (std::size_t i = 0; i < count; ++i) {
            const double depth = depthOf(rng);
            const Vec3 onPlane = o.origin + Vec3(depth * tanH, 4.0 * (unit(rng) - 0.5), -depth);  // on the right plane
            KeyframeBehaviour::Actor a;
            a.tmpl = tmpl;
            a.heading = 2.0 * std::numbers::pi * unit(rng);
            const double cosA = std::cos(a.heading), sinA = std::sin(a.heading);
            auto turn = [&](const Vec3& v) { return Vec3(cosA * v.x + sinA * v.z, v.y, -sinA * v.x + cosA * v.z); };
            Vec3 skls;  // where the Skeleton Root must stand
            const double rSk = tmpl->skeletonRootRadius();
            const double gap = 0.2 + 0.5 * unit(rng);
            switch (cls) {
                case 0:  // A: the Refpoint Bsphere wholly outside the right plane
                case 1: {  // B: wholly inside
                    const double side = cls == 0 ? -1.0 : 1.0;
                    const Vec3 centre = onPlane + n * (side * (rRef + 0.5 + 10.0 * unit(rng)));
                    skls = centre - turn(extentCentre) + turn(Vec3(offset));
                    break;
                }
                case 2:  // C1: the offset points out of the frustum, the Sklsroot sphere just outside
                    a.heading = heading(-n);
                    skls = onPlane - n * (rSk + std::min(gap, 0.5 * offsetLength));
                    break;
                case 3:  // C2: the offset points in, the Sklsroot sphere just inside
                    a.heading = heading(n);
                    skls = onPlane + n * (rSk + std::min(gap, 0.5 * offsetLength));
                    break;
                default: {  // C3: the Sklsroot sphere crosses; place the internal spheres' bound
                    a.heading = heading(along);  // the offset along the plane keeps the Refpoint Bsphere crossing it
                    const double cosH = std::cos(a.heading), sinH = std::sin(a.heading);
                    const Vec3 c(whole.center());
                    const Vec3 cw(cosH * c.x + sinH * c.z, c.y, -sinH * c.x + cosH * c.z);  // rotated about +Y
                    const bool inside = i % 2 == 0;
                    const double target = cls == 4 ? (inside ? 1.0 : -1.0) * (whole.radius() + 0.02) : 0.0;
                    skls = onPlane + n * (target - glm::dot(n, cw));
                    if (std::abs(glm::dot(n, skls - onPlane)) >= rSk - 0.01)
                        throw std::invalid_argument("buildCostModelScene: the Sklsroot margin of template '" + tmpl->name() +
                                                    "' leaves no room for class C3");
                }
            }
            // Reference Point = Skeleton Root minus the clip's offset turned by the heading.
            const double cosH = std::cos(a.heading), sinH = std::sin(a.heading);
            const Vec3 o3(offset);
            a.position = skls - Vec3(cosH * o3.x + sinH * o3.z, o3.y, -sinH * o3.x + cosH * o3.z);
            const ActorId id = crowd.add(tmpl, behaviour, behaviour->addActor(a));
            scene.byClass[static_cast<std::size_t>(cls)].push_back(id);
        }
    };
    const std::size_t counts[6] = {o.counts.a, o.counts.b, o.counts.c1, o.counts.c2, o.counts.c3_1, o.counts.c3_2};
    for (int cls = 0; cls < 6; ++cls) place(cls, counts[cls]);
    std::vector<ActorId> all;
    for (const auto& ids : scene.byClass) all.insert(all.end(), ids.begin(), ids.end());
    if (o.group) scene.root->addChild(crowd.makeGroupNode(all));
    else
        for (ActorId id : all) scene.root->addChild(crowd.makeActorNode(id));
    return scene;
}

CostModelScene buildTable2Scene(Crowd& crowd, std::size_t actors) {
    CostModelSceneOptions options;
    options.counts = CascadeCounts::scaled(actors);
    options.group = true;
    return buildCostModelScene(crowd, makeTable3Template(), std::make_shared<KeyframeBehaviour>(), options);
}

}  // namespace throng
