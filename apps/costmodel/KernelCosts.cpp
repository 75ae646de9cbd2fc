#include "KernelCosts.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "throng/actors/Crowd.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/detail/ClipKernels.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/SphereArrayCuller.h"
#include "throng/scenegraph/Transform.h"

namespace throng::costmodel {
namespace {

// Records `cost` as the cost of `kernel`, or checks that it is the same as the one recorded.
void uniform(std::map<std::string, OpTally>& kernels, const std::string& kernel, const OpTally& cost) {
    const auto [it, added] = kernels.emplace(kernel, cost);
    if (!added && !(it->second == cost))
        throw std::runtime_error("cost model check: kernel '" + kernel + "' does not cost the same for every actor of the example scene");
}

template <class F>
OpTally tallyOf(F&& f) {
    OpTally t;
    f(&t);
    return t;
}

bool posed(ActorClass c) { return c == ActorClass::B || c == ActorClass::C2 || c == ActorClass::C3_1 || c == ActorClass::C3_2; }

}  // namespace

KernelFigures measureKernels(const CostModelScene& scene, const Crowd& crowd, const ProcessorSettings& settings,
                             const DrawList& actorDrawList, const ActorFrameStatistics& traditionalStats,
                             const ActorFrameStatistics& actorStats) {
    KernelFigures f;
    auto& k = f.kernels;
    const Crowd::State& s = crowd.state();
    const Vec3 eye = scene.camera.eye();
    const double lodScale2 = settings.lodScale * settings.lodScale;

    // Fixed-cost kernels, on the scene's data.
    if (crowd.size() == 0) throw std::invalid_argument("measureKernels: the crowd has no actor to measure on");
    const Mat4& someMatrix = crowd.referencePoint(0);
    k["composeAffine"] = tallyOf([&](OpTally* t) { composeAffine(someMatrix, someMatrix, t); });
    k["rootPoseMatrix"] = tallyOf([&](OpTally* t) { rootPoseMatrix(s.root[0], t); });
    k["compose"] = tallyOf([&](OpTally* t) { compose(Affine{}, Affine{}, t); });
    k["detailDistanceSquared"] = tallyOf([&](OpTally* t) { detailDistanceSquared(someMatrix, eye, lodScale2, 1.0f, t); });
    k["eyeDistance"] = tallyOf([&](OpTally* t) { eyeDistance(someMatrix, eye, t); });
    // Spheres: a transform, and a merge of each kind; frustum planes; the flat-array culler.
    const BoundingSphere unit(Vec3(0.0), 1.0);
    k["sphereTransform"] = tallyOf([&](OpTally* t) { unit.transformed(someMatrix, t); });
    k["sphereMergeFull"] = tallyOf([&](OpTally* t) { BoundingSphere(unit).expandBy(BoundingSphere(Vec3(5, 0, 0), 1.0), t); });
    k["sphereMergeContained"] = tallyOf([&](OpTally* t) { BoundingSphere(unit).expandBy(BoundingSphere(Vec3(0.1, 0, 0), 0.5), t); });
    k["sphereMergeInsideOther"] = tallyOf([&](OpTally* t) { BoundingSphere(Vec3(0.1, 0, 0), 0.5).expandBy(unit, t); });
    // One plane (the left one of the clip cube): a test with no plane left, one plane passed, one
    // plane failed; each includes the sphere's emptiness test.
    const Frustum cube = Frustum::fromViewProjection(Mat4(1.0));
    auto classify = [&](const BoundingSphere& sphere, PlaneMask mask) {
        return tallyOf([&](OpTally* t) { cube.classify(sphere, mask, t); });
    };
    k["classifyNoPlane"] = classify(BoundingSphere(Vec3(0.0), 0.1), 0);
    k["classifyOnePlaneNotOutside"] = classify(BoundingSphere(Vec3(0.0), 0.1), 1u << Frustum::kLeft);
    k["classifyOnePlaneOutside"] = classify(BoundingSphere(Vec3(-5, 0, 0), 0.1), 1u << Frustum::kLeft);
    k["flatArraySphere"] = SphereArrayCuller::kOpsPerSphere;

    // Key-framing and Reference Points, actor by actor: the same for every actor of the scene.
    const ActorTemplate& tmpl = *s.tmpl[scene.byClass[0].empty() ? 0 : scene.byClass[0][0]];
    const AnimationClip& clip = *tmpl.clips()[0];
    double channels = 0;
    for (const ClipChannel& c : clip.channels()) channels += c.target == ClipChannel::Target::NodeDof;
    // Key searches of a sample: one per run of channels (active ones only) sharing key times.
    auto keySearches = [&](std::span<const std::uint8_t> active) {
        double searches = 0;
        std::uint32_t searched = ~std::uint32_t{0};
        for (std::size_t i = 0; i < clip.channels().size(); ++i) {
            const ClipChannel& c = clip.channels()[i];
            if (c.target != ClipChannel::Target::NodeDof || (!active.empty() && !active[c.node])) continue;
            if (clip.timeSources()[i] != searched) searched = clip.timeSources()[i], searches += 1;
        }
        return searches;
    };
    std::size_t roots = 0, geometryNodes = 0;
    for (const SkeletonNode& n : tmpl.nodes()) roots += n.parent < 0, geometryNodes += n.geometrySphere.valid();
    for (ActorId id = 0; id < crowd.size(); ++id) {
        if (s.tmpl[id] != &tmpl) throw std::runtime_error("cost model check: the example scene has more than one template");
        Behaviour& b = *s.behaviour[id];
        const FrameContext context{scene.time, 0.0, 0, nullptr};
        uniform(k, "refpointPath", tallyOf([&](OpTally* t) { b.referencePoint(s.slot[id], context, t); }));
        const double clipTime = b.clipTime(s.slot[id], scene.time);
        uniform(k, "clipLocalTime", tallyOf([&](OpTally* t) { detail::clipLocalTime(clip.duration(), clipTime, true, t); }));
        for (bool hold : {false, true}) {
            const std::string held = hold ? "Held" : "";
            uniform(k, "clipRoot" + held, tallyOf([&](OpTally* t) { clip.sampleRoot(clipTime, true, t, hold); }));
            const float ft = static_cast<float>(clip.localTime(clipTime, true));
            for (const ClipChannel& c : clip.channels()) {
                if (c.target != ClipChannel::Target::NodeDof) continue;
                const DofKind kind = tmpl.nodes()[c.node].dofs[c.dof].kind;
                std::vector<float> out(4);
                // The key search is shared by a run of channels with the same key times (see
                // detail::sampleClip): priced apart from the sample that follows it.
                const std::size_t upper = detail::keyAfter(c.times, ft, nullptr);
                uniform(k, "clipKeySearch", tallyOf([&](OpTally* t) { detail::keyAfter(c.times, ft, t); }));
                uniform(k, "clipChannel" + held, tallyOf([&](OpTally* t) {
                            detail::sampleChannelAt(c, dofValueCount(kind), kind == DofKind::Orientation, ft, upper, out.data(), t,
                                                    hold);
                        }));
            }
        }
        const auto dofs = std::span<const float>(s.dofs).subspan(s.dofOffset[id], tmpl.dofValueCount());
        for (std::size_t i = 0; i < tmpl.nodeCount(); ++i)
            uniform(k, "nodeLocalTransform", tallyOf([&](OpTally* t) { nodeLocalTransform(tmpl.nodes()[i], dofs.data() + tmpl.dofOffset(i), t); }));
    }

    // Traditional processing: every actor at level 0, every node.
    auto& tr = f.traditional;
    tr["actors"] = double(traditionalStats.actorsInScene);
    tr["nodesPerActor"] = double(tmpl.nodeCount());
    tr["rootNodesPerActor"] = double(roots);
    tr["channelsPerActor"] = channels;
    tr["keySearchesPerActor"] = keySearches({});
    tr["lodDistances"] = double(traditionalStats.lodDistances);
    // At least: every node's geometry sphere and the actor-level bound, placed in the world.
    tr["sphereTransformsAtLeast"] = double(traditionalStats.actorsInScene) * double(geometryNodes + (tmpl.rootGeometry().bound().valid() ? 1 : 0));

    // Actor processing: who was posed at which behavioural level, with how many active nodes.
    auto& ac = f.actor;
    ac["actors"] = double(actorStats.actorsInScene);
    ac["lodDistances"] = double(actorStats.lodDistances);
    double survivorsAt[3] = {0, 0, 0}, posedAt[3] = {0, 0, 0}, nodes = 0, rootsPosed = 0, channelsAt[3] = {0, 0, 0},
           searchesAt[3] = {0, 0, 0};
    double c3Transforms = 0;
    for (ActorId id = 0; id < crowd.size(); ++id) {
        const ActorClass c = s.actorClass[id];
        if (c == ActorClass::A || c == ActorClass::NotInScene || c == ActorClass::CulledWithGroup) continue;
        const Behaviour& b = *s.behaviour[id];
        // Phase 3 chooses the Skeleton Root's level by the Reference Point's distance.
        const Vec3 d = s.refSphereWorld[id].center() - eye;
        survivorsAt[settings.behaviouralLod ? std::min(2, b.levelFor(std::sqrt(glm::dot(d, d) * lodScale2) / s.priority[id])) : 0] += 1;
        if (!posed(c)) continue;
        const double d2 = detailDistanceSquared(s.sklsWorld[id], eye, lodScale2, s.priority[id]);
        const int level = settings.behaviouralLod ? std::min(2, b.levelFor(std::sqrt(d2))) : 0;
        std::vector<std::uint8_t> active(tmpl.nodeCount());
        if (settings.skeletalLod) computeActiveNodes(tmpl, d2, active);
        else std::fill(active.begin(), active.end(), std::uint8_t{1});
        posedAt[level] += 1;
        for (std::size_t i = 0; i < tmpl.nodeCount(); ++i) {
            if (!active[i]) continue;
            nodes += 1;
            rootsPosed += tmpl.nodes()[i].parent < 0;
            if (c == ActorClass::C3_1 || c == ActorClass::C3_2) c3Transforms += tmpl.nodes()[i].geometrySphere.valid();
        }
        for (const ClipChannel& ch : clip.channels()) channelsAt[level] += ch.target == ClipChannel::Target::NodeDof && active[ch.node];
        searchesAt[level] += keySearches(active);
        if (c == ActorClass::C3_1 || c == ActorClass::C3_2) c3Transforms += 1;  // the whole internal bound, placed in the world
    }
    for (int level = 0; level < 3; ++level) {
        ac["survivorsAtLevel" + std::to_string(level)] = survivorsAt[level];
        ac["posedAtLevel" + std::to_string(level)] = posedAt[level];
        ac["channelsAtLevel" + std::to_string(level)] = channelsAt[level];
        ac["keySearchesAtLevel" + std::to_string(level)] = searchesAt[level];
    }
    ac["posedNodes"] = nodes;
    ac["posedRootNodes"] = rootsPosed;
    // Phase 7 composes a world matrix for every node part it draws.
    double nodeItems = 0;
    for (const DrawItem& item : actorDrawList.items()) nodeItems += item.part < tmpl.nodeCount();
    ac["nodeDrawItems"] = nodeItems;
    ac["sphereTransformsAtLeast"] = double(actorStats.actorsInScene) + c3Transforms;
    // The scene holds one Actor node per actor (no ActorGroup), so no member is culled in the flat arrays.
    ac["flatArraySpheres"] = 0;
    ac["rejectedOutside"] = double(actorStats.a + actorStats.c1);
    return f;
}

}  // namespace throng::costmodel
