#include "throng/actors/ActorProcessor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ActorDrawItem.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/AppVisitor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/CullVisitor.h"
#include "throng/scenegraph/DrawBackend.h"
#include "throng/scenegraph/MatrixBoundsVisitor.h"
#include "throng/scenegraph/Node.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/scenegraph/SphereArrayCuller.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/scenegraph/Transform.h"
#include "throng/scenegraph/Validation.h"

namespace throng {
namespace {

// A standard traversal that offers actor processing to the Actor and ActorGroup nodes it meets.
template <class Base>
class WithActorTraversal : public Base {
public:
    template <class... Args>
    explicit WithActorTraversal(ActorTraversal* traversal, Args&&... args) : Base(std::forward<Args>(args)...) {
        this->setExtension(&ActorTraversal::kKey, traversal);
    }
};

// Candidate stages.
constexpr std::uint8_t kPending = 0, kInside = 1, kCrossing = 2, kOutside = 3;
// Visibility of a survivor's parts after CULL 3.
constexpr std::uint8_t kNoneVisible = 0, kAllVisible = 1, kPerPart = 2;
constexpr PlaneMask kCulled = 0xFF;

std::span<float> dofsOf(Crowd::State& s, ActorId id) {
    return std::span<float>(s.dofs).subspan(s.dofOffset[id], s.tmpl[id]->dofValueCount());
}

// The node a held object is drawn with: its own, or its nearest active ancestor.
int holderNode(const ActorTemplate& t, std::span<const std::uint8_t> active, int node) {
    while (node >= 0 && !active[static_cast<std::size_t>(node)]) node = t.nodes()[static_cast<std::size_t>(node)].parent;
    return node;
}

}  // namespace

ActorProcessor::ActorProcessor(Crowd& crowd) : crowd_(crowd) {}

void ActorProcessor::setLodScale(double scale) {
    traditional_.setLodScale(scale);  // validates
    lodScale_ = scale;
}

void ActorProcessor::setCullingFrustum(std::optional<Frustum> frustum) {
    traditional_.setCullingFrustum(frustum);
    cullingFrustum_ = frustum;
}

void ActorProcessor::setThreads(unsigned threads) {
    if (threads == 0) throw std::invalid_argument("ActorProcessor::setThreads: argument 'threads' must be at least 1");
    pool_ = threads > 1 ? std::make_unique<WorkerPool>(threads) : nullptr;
}

void ActorProcessor::forRanges(std::size_t n, bool counting, const std::function<void(std::size_t, std::size_t)>& body) {
    if (pool_ && !counting) pool_->parallelFor(n, body);
    else if (n) body(0, n);
}

const DrawList& ActorProcessor::drawList() const {
    return stats_.processing == Processing::Traditional ? traditional_.drawList() : drawList_;
}

const ActorFrameStatistics& ActorProcessor::processFrame(Node& root, const Camera& camera, double time,
                                                         DrawBackend* backend) {
    requireFinite(time, "ActorProcessor::processFrame", "time");
    const std::uint64_t framesBegun = crowd_.framesBegun();
    if (processing_ == Processing::Actor) {
        processActors(root, camera, time, backend);
    } else {
        const FrameStatistics& f = traditional_.processFrame(root, camera, time, backend);
        stats_ = ActorFrameStatistics{};
        stats_.processing = Processing::Traditional;
        stats_.frame = frame_;
        // The behaviours' step ran inside APP (the first actor node began the frame).
        const double step = crowd_.framesBegun() != framesBegun ? crowd_.lastStepMs() : 0.0;
        stats_.appMs = std::max(0.0, f.appMs - step);
        stats_.matricesBoundsMs = f.matricesBoundsMs;
        stats_.cullMs = f.cullMs;
        stats_.drawMs = f.drawMs;
        const Crowd::State& s = crowd_.state();
        for (std::size_t id = 0; id < crowd_.size(); ++id)
            if (s.owner[id]) {
                ++stats_.actorsInScene;
                stats_.skeletonNodesEvaluated += s.tmpl[id]->nodeCount();
            }
        stats_.actorsPosed = stats_.actorsInScene;
        stats_.internalSpheresComputed = f.matrices.spheresRecomputed;
        stats_.spheresTested = f.cull.spheresTested;
        stats_.lodDistances = f.cull.lodDistances;
        stats_.drawItems = f.cull.drawItems;
        stats_.primitives = f.cull.primitives;
        stats_.fmultTotal = f.fmultTotal;
    }
    if (crowd_.framesBegun() != framesBegun) stats_.stepMs = crowd_.lastStepMs();
    lastTime_ = time;
    ++frame_;
    return stats_;
}

BoundingSphere ActorProcessor::bound(Node&, std::span<const ActorId> ids, MatrixBoundsVisitor& visitor) {
    Crowd::State& s = crowd_.state();
    OpCounter* c = visitor.counter();
    OpTally* refOps = tallyFor(c, OpCategory::RefpointMatrix);
    OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
    const Mat4& parent = visitor.parentWorld();
    const bool identity = visitor.parentIsIdentity();
    BoundingSphere group;
    for (ActorId id : ids) {
        s.refWorld[id] = identity ? s.refLocal[id] : composeAffine(parent, s.refLocal[id], refOps);
        s.refSphereWorld[id] = s.refSphereLocal[id].transformed(s.refWorld[id], sphereOps);
        group.expandBy(s.refSphereWorld[id], ids.size() > 1 ? sphereOps : nullptr);
    }
    countOperations(c, OpCategory::RefpointMatrix, ids.size());
    countOperations(c, OpCategory::BsphereRecompute, ids.size());
    visitor.statistics().worldMatricesComposed += ids.size();
    visitor.statistics().spheresRecomputed += ids.size();
    return group;
}

void ActorProcessor::cull(Node& node, std::span<const ActorId> ids, CullVisitor& visitor) {
    const PlaneMask mask = visitor.planeMask();
    // A lone actor's node bound is its Refpoint Bsphere, which the traversal just tested (CULL 1);
    // so is a group's when every member is inside the planes the group crosses.
    const bool decided = ids.size() == 1 || mask == 0;
    for (std::uint32_t member = 0; member < ids.size(); ++member) {
        const std::uint8_t stage = !decided ? kPending : mask == 0 ? kInside : kCrossing;
        candidates_.push_back(Candidate{ids[member], &node, member, mask, stage});
    }
}

void ActorProcessor::culledOut(Node&, std::span<const ActorId> ids, CullVisitor&) {
    // Every Refpoint Bsphere lies inside the node's bound, so every one is outside too.
    Crowd::State& s = crowd_.state();
    for (ActorId id : ids) s.actorClass[id] = ActorClass::A;
    stats_.a += ids.size();
}

void ActorProcessor::cullRefpoints(const Frustum& frustum, const Vec3& eye) {
    // Phase 2 for members of groups that cross the frustum: their Refpoint Bspheres, flat, several
    // at a time, relative to the eye.
    const Crowd::State& s = crowd_.state();
    cx_.clear(), cy_.clear(), cz_.clear(), cr_.clear();
    for (const Candidate& c : candidates_) {
        if (c.pending != kPending) continue;
        const BoundingSphere& b = s.refSphereWorld[c.id];
        const Vec3 rel = b.center() - eye;
        cx_.push_back(static_cast<float>(rel.x));
        cy_.push_back(static_cast<float>(rel.y));
        cz_.push_back(static_cast<float>(rel.z));
        cr_.push_back(static_cast<float>(b.radius()));
    }
    if (cx_.empty()) return;
    containment_.resize(cx_.size());
    OpCounter* c = counter().enabled() ? &counter() : nullptr;
    SphereArrayCuller(frustum, eye).classify({cx_, cy_, cz_, cr_}, containment_, tallyFor(c, OpCategory::BsphereFrustumTest));
    countOperations(c, OpCategory::BsphereFrustumTest, cx_.size());
    stats_.spheresTested += cx_.size();
    std::size_t k = 0;
    for (Candidate& cand : candidates_) {
        if (cand.pending != kPending) continue;
        switch (containment_[k++]) {
            case Containment::Outside: cand.pending = kOutside; break;
            case Containment::Inside: cand.pending = kInside, cand.mask = 0; break;
            case Containment::Intersects: cand.pending = kCrossing; break;
        }
    }
}

void ActorProcessor::setImpostorDistance(double distance, double hysteresis) {
    if (!(distance >= 0.0) || !std::isfinite(distance) || !(hysteresis >= 0.0) || !std::isfinite(hysteresis))
        throw std::invalid_argument("ActorProcessor::setImpostorDistance: distance and hysteresis must be finite and >= 0");
    impostorDistance_ = distance;
    impostorHysteresis_ = hysteresis;
    if (distance == 0.0) impostorTier_.clear();
}

void ActorProcessor::setImpostor(const ActorTemplate& tmpl, std::shared_ptr<const Drawable> impostor) {
    std::erase_if(impostors_, [&](const auto& e) { return e.first == &tmpl; });
    if (impostor) impostors_.emplace_back(&tmpl, std::move(impostor));
}

bool ActorProcessor::impostorTier(ActorId id, const ActorTemplate& tmpl, double detail2, const Candidate& cand) {
    const Drawable* impostor = nullptr;
    for (const auto& [t, d] : impostors_)
        if (t == &tmpl) impostor = d.get();
    if (impostorTier_.size() < crowd_.size()) impostorTier_.resize(crowd_.size(), 0);
    if (!impostor) return impostorTier_[id] = 0, false;
    // Hysteresis on squared distances: no square root per actor.
    const double out = impostorDistance_ + impostorHysteresis_, in = std::max(impostorDistance_ - impostorHysteresis_, 0.0);
    std::uint8_t& tier = impostorTier_[id];
    if (tier != 0 && detail2 < in * in) tier = 0;
    else if (tier == 0 && detail2 > out * out) tier = 1;
    if (tier == 0) return false;
    Crowd::State& s = crowd_.state();
    drawList_.add(detail::actorPartItem(cand.node, cand.member, s.tint[id], *impostor, &s.refWorld[id],
                                        static_cast<std::uint32_t>(tmpl.nodeCount()), 0),
                  impostor->primitiveCount());
    ++stats_.impostors;
    ++stats_.drawItems;
    stats_.primitives += impostor->primitiveCount();
    return true;
}

void ActorProcessor::processActors(Node& root, const Camera& camera, double time, DrawBackend* backend) {
    Crowd::State& s = crowd_.state();
    OpCounter& counterRef = counter();
    counterRef.reset();
    OpCounter* c = counterRef.enabled() ? &counterRef : nullptr;
    stats_ = ActorFrameStatistics{};
    stats_.processing = Processing::Actor;
    stats_.frame = frame_;
    const FrameContext context{time, frame_ == 0 ? 0.0 : time - lastTime_, frame_, c};
    crowd_.beginFrame(context);
    drawList_.clear();
    candidates_.clear();
    const double lodScale2 = lodScale_ * lodScale_;
    const Frustum frustum = cullingFrustum_ ? *cullingFrustum_ : camera.frustum();
    const Vec3& eye = camera.eye();

    // Generic APP: callbacks of generic nodes; actor nodes wait for phase 1.
    Stopwatch watch;
    WithActorTraversal<AppVisitor> app(this, context);
    root.accept(app);
    stats_.appMs = watch.elapsedMs();

    // Phase 1: the Reference Point of every actor, in the scene or not, whatever the camera.
    watch.restart();
    OpTally* refOps = tallyFor(c, OpCategory::RefpointDofValues);
    forRanges(crowd_.size(), c != nullptr, [&](std::size_t begin, std::size_t end) {
        for (std::size_t id = begin; id < end; ++id) s.refLocal[id] = s.behaviour[id]->referencePoint(s.slot[id], context, refOps);
    });
    for (std::size_t id = 0; id < crowd_.size(); ++id) {
        s.eyeDistance[id] = std::numeric_limits<double>::infinity();
        const bool inScene = s.owner[id] != nullptr;
        s.actorClass[id] = inScene ? ActorClass::CulledWithGroup : ActorClass::NotInScene;
        stats_.actorsInScene += inScene;
    }
    for (Node* node : crowd_.nodes()) node->dirtyBound();  // every actor moved
    stats_.refpointMs = watch.elapsedMs();

    // Generic matrices and bounds; actor nodes place their Refpoint Bspheres in the world.
    watch.restart();
    WithActorTraversal<MatrixBoundsVisitor> matrices(this, c, false);
    root.accept(matrices);
    stats_.matricesBoundsMs = watch.elapsedMs();
    stats_.internalSpheresComputed += matrices.statistics().spheresRecomputed;

    // Generic CULL, which meets the actor nodes after the generic groups above them, and CULL 1.
    watch.restart();
    WithActorTraversal<CullVisitor> cull(this, camera, drawList_, c, lodScale_);
    if (cullingFrustum_) cull.setCullingFrustum(*cullingFrustum_);
    root.accept(cull);
    cullRefpoints(frustum, eye);
    survivors_.clear();
    for (std::size_t k = 0; k < candidates_.size(); ++k) {
        const Candidate& cand = candidates_[k];
        if (cand.pending == kOutside) {
            s.actorClass[cand.id] = ActorClass::A;
            ++stats_.a;
        } else {
            survivors_.push_back(k);
        }
    }
    stats_.cullMs = watch.elapsedMs();
    stats_.spheresTested += cull.statistics().spheresTested;
    stats_.lodDistances += cull.statistics().lodDistances;
    stats_.culledWithGroup = stats_.actorsInScene - candidates_.size() - (stats_.a - (candidates_.size() - survivors_.size()));

    // Phase 3: Skeleton Roots of the survivors.
    watch.restart();
    OpTally* rootOps = tallyFor(c, OpCategory::SkeletonRootMatrix);
    OpTally* rootValueOps = tallyFor(c, OpCategory::SkeletonRootDofValues);
    forRanges(survivors_.size(), c != nullptr, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const ActorId id = candidates_[survivors_[k]].id;
            Behaviour& b = *s.behaviour[id];
            int level = 0;
            if (behaviouralLod_) {  // the Skeleton Root is not placed yet: judge by the Reference Point
                const Vec3 d = s.refSphereWorld[id].center() - eye;
                level = b.levelFor(std::sqrt(glm::dot(d, d) * lodScale2) / s.priority[id]);
            }
            s.root[id] = b.skeletonRoot(s.slot[id], time, level, rootValueOps);
            s.sklsWorld[id] = composeAffine(s.refWorld[id], rootPoseMatrix(s.root[id], rootOps), rootOps);
        }
    });
    countOperations(c, OpCategory::SkeletonRootMatrix, survivors_.size());
    stats_.skeletonRootMs = watch.elapsedMs();

    // Phase 4: CULL 2 on Sklsroot Bspheres of actors whose Refpoint Bsphere crosses; one eye distance
    // per actor; skeletal LOD.
    watch.restart();
    OpTally* testOps = tallyFor(c, OpCategory::BsphereFrustumTest);
    OpTally* lodOps = tallyFor(c, OpCategory::LodDistance);
    std::size_t kept = 0;
    std::uint32_t nodes = 0;
    detail2_.resize(survivors_.size());
    level_.resize(survivors_.size());
    nodeBase_.resize(survivors_.size());
    for (std::size_t k : survivors_) {
        Candidate& cand = candidates_[k];
        const ActorId id = cand.id;
        if (cand.pending == kCrossing) {
            const BoundingSphere skls(Vec3(s.sklsWorld[id][3]), s.sklsRadius[id]);
            ++stats_.spheresTested;
            countOperations(c, OpCategory::BsphereFrustumTest);
            const Containment r = frustum.classify(skls, cand.mask, testOps);
            if (r == Containment::Outside) {
                s.actorClass[id] = ActorClass::C1;
                ++stats_.c1;
                continue;
            }
            s.actorClass[id] = r == Containment::Inside ? ActorClass::C2 : ActorClass::C3_1;  // C3 refined in phase 6
            if (r == Containment::Inside) ++stats_.c2;
        } else {
            s.actorClass[id] = ActorClass::B;
            ++stats_.b;
        }
        const double d2 = detailDistanceSquared(s.sklsWorld[id], eye, lodScale2, s.priority[id], lodOps);
        s.eyeDistance[id] = glm::length(Vec3(s.sklsWorld[id][3]) - eye);
        THRONG_TALLY(lodOps, 3, 5, 0, 1);
        countOperations(c, OpCategory::LodDistance);
        ++stats_.lodDistances;
        const ActorTemplate& t = *s.tmpl[id];
        if (impostorDistance_ > 0.0 && impostorTier(id, t, d2, cand)) continue;
        detail2_[kept] = d2;
        level_[kept] = behaviouralLod_ ? s.behaviour[id]->levelFor(std::sqrt(d2)) : 0;
        nodeBase_[kept] = nodes;
        nodes += static_cast<std::uint32_t>(t.nodeCount());
        survivors_[kept++] = k;
    }
    survivors_.resize(kept);
    active_.resize(nodes);
    model_.resize(nodes);
    for (std::size_t j = 0; j < survivors_.size(); ++j) {
        const ActorTemplate& t = *s.tmpl[candidates_[survivors_[j]].id];
        const std::span<std::uint8_t> active(active_.data() + nodeBase_[j], t.nodeCount());
        if (skeletalLod_) computeActiveNodes(t, detail2_[j], active);
        else std::fill(active.begin(), active.end(), std::uint8_t{1});
    }
    stats_.cull2Ms = watch.elapsedMs();

    // Phase 5: behaviour of the active Skeleton nodes, at each actor's level, and their matrices.
    watch.restart();
    OpTally* nodeOps = tallyFor(c, OpCategory::SkeletonMatrix);
    OpTally* valueOps = tallyFor(c, OpCategory::SkeletonDofValues);
    evaluated_.resize(survivors_.size());
    forRanges(survivors_.size(), c != nullptr, [&](std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
            const ActorId id = candidates_[survivors_[j]].id;
            const ActorTemplate& t = *s.tmpl[id];
            const std::span<const std::uint8_t> active(active_.data() + nodeBase_[j], t.nodeCount());
            s.behaviour[id]->pose(s.slot[id], time, level_[j], t, active, dofsOf(s, id), valueOps);
            evaluated_[j] = static_cast<std::uint32_t>(computeModelTransforms(
                t, dofsOf(s, id), active, std::span<Affine>(model_.data() + nodeBase_[j], t.nodeCount()), nodeOps));
        }
    });
    for (std::uint32_t evaluated : evaluated_) {
        countOperations(c, OpCategory::SkeletonMatrix, evaluated);
        stats_.skeletonNodesEvaluated += evaluated;
    }
    stats_.actorsPosed = survivors_.size();
    stats_.poseMs = watch.elapsedMs();

    // Phase 6: CULL 3, only for actors whose Sklsroot Bsphere crosses a plane.
    watch.restart();
    geometry_.resize(nodes);
    subtree_.resize(nodes);
    masks_.resize(nodes);
    visible_.assign(nodes + 1, 0);  // per node, and one for the actor-level geometry of the survivor being culled
    std::vector<std::uint8_t>& visible = visible_;
    level_.resize(survivors_.size());
    std::vector<std::uint8_t> state(survivors_.size(), kAllVisible);
    std::vector<std::uint8_t> rootVisible(survivors_.size(), 1);
    OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
    for (std::size_t j = 0; j < survivors_.size(); ++j) {
        const Candidate& cand = candidates_[survivors_[j]];
        const ActorId id = cand.id;
        if (s.actorClass[id] != ActorClass::C3_1) continue;  // B and C2 are wholly inside
        const ActorTemplate& t = *s.tmpl[id];
        const std::size_t n = t.nodeCount();
        const std::uint32_t base = nodeBase_[j];
        const std::span<const std::uint8_t> active(active_.data() + base, n);
        const std::span<const Affine> model(model_.data() + base, n);
        BoundingSphere whole = computeInternalSpheres(t, model, active, std::span(geometry_.data() + base, n),
                                                      std::span(subtree_.data() + base, n), sphereOps);
        std::size_t computed = 1;
        for (std::size_t i = 0; i < n; ++i)
            if (active[i]) computed += 1 + (geometry_[base + i].valid() ? 1 : 0);
        if (s.held[id] >= 0)
            for (const HeldObject& h : s.heldObjects[static_cast<std::size_t>(s.held[id])]) {
                const int holder = holderNode(t, active, h.node);
                const BoundingSphere sphere = holder < 0 ? h.drawable->localBound()
                                                         : h.drawable->localBound().transformed(
                                                               model[static_cast<std::size_t>(holder)].toDMat4(), sphereOps);
                for (int a = holder; a >= 0; a = t.nodes()[static_cast<std::size_t>(a)].parent)
                    subtree_[base + static_cast<std::size_t>(a)].expandBy(sphere, sphereOps);
                whole.expandBy(sphere, sphereOps);
            }
        countOperations(c, OpCategory::BsphereRecompute, computed);
        stats_.internalSpheresComputed += computed;
        const Mat4& skls = s.sklsWorld[id];
        PlaneMask mask = cand.mask;
        ++stats_.spheresTested;
        countOperations(c, OpCategory::BsphereFrustumTest);
        const Containment r = frustum.classify(whole.transformed(skls, sphereOps), mask, testOps);
        if (r != Containment::Intersects) {
            state[j] = r == Containment::Inside ? kAllVisible : kNoneVisible;
            ++stats_.c3_1;
            continue;
        }
        s.actorClass[id] = ActorClass::C3_2;
        ++stats_.c3_2;
        state[j] = kPerPart;
        auto test = [&](const BoundingSphere& sphere, PlaneMask& m) {
            ++stats_.spheresTested;
            countOperations(c, OpCategory::BsphereFrustumTest);
            return frustum.classify(sphere, m, testOps) != Containment::Outside;
        };
        // The actor-level geometry, then each active node depth first, as traditional CULL does.
        const double d2 = detail2_[j];
        const int rootLevel = t.rootGeometry().selectSquared(d2);
        if (rootLevel >= 0) {
            const VaLodLevel& lv = t.rootGeometry().levels()[static_cast<std::size_t>(rootLevel)];
            PlaneMask m = mask;
            // A skinned mesh's sphere is its joints' (the whole internal bound just found crossing).
            rootVisible[j] = lv.drawable && (lv.skin >= 0 || test(lv.drawable->localBound().transformed(skls, sphereOps), m));
        }
        const auto tnodes = t.nodes();
        for (std::size_t i = 0; i < n; ++i) {
            if (!active[i]) {
                i = t.subtreeEnd(i) - 1;
                continue;
            }
            const int p = tnodes[i].parent;
            PlaneMask m = p < 0 ? mask : masks_[base + static_cast<std::size_t>(p)];
            if (!test(subtree_[base + i].transformed(skls, sphereOps), m)) {
                masks_[base + i] = kCulled;
                for (std::size_t k = i; k < t.subtreeEnd(i); ++k) visible[base + k] = 0;
                i = t.subtreeEnd(i) - 1;
                continue;
            }
            masks_[base + i] = m;
            const VaLod& lod = tnodes[i].geometry;
            const int level = lod.selectSquared(d2);
            const auto* drawable = level >= 0 ? lod.levels()[static_cast<std::size_t>(level)].drawable.get() : nullptr;
            PlaneMask leaf = m;
            visible[base + i] = drawable && geometry_[base + i].valid() &&
                                test(geometry_[base + i].transformed(skls, sphereOps), leaf) &&
                                test(partWorldSphere(drawable->localBound(), model[i], skls, sphereOps), leaf);
        }
    }
    stats_.cull3Ms = watch.elapsedMs();

    // Phase 7: the draw list.
    watch.restart();
    FrameArena<Mat4>& arena = crowd_.drawMatrices();
    for (std::size_t j = 0; j < survivors_.size(); ++j) {
        if (state[j] == kNoneVisible) continue;
        const Candidate& cand = candidates_[survivors_[j]];
        const ActorId id = cand.id;
        const ActorTemplate& t = *s.tmpl[id];
        const std::size_t n = t.nodeCount();
        const std::uint32_t base = nodeBase_[j];
        const std::span<const std::uint8_t> active(active_.data() + base, n);
        const Mat4& skls = s.sklsWorld[id];
        const double d2 = detail2_[j];
        const bool all = state[j] == kAllVisible;
        auto emit = [&](const Drawable& d, const Mat4* world, std::uint32_t part, int level,
                        const glm::mat4* palette = nullptr, std::size_t paletteSize = 0) {
            drawList_.add(detail::actorPartItem(cand.node, cand.member, s.tint[id], d, world, part, level, palette, paletteSize),
                          d.primitiveCount());
            ++stats_.drawItems;
            stats_.primitives += d.primitiveCount();
        };
        const int rootLevel = t.rootGeometry().selectSquared(d2);
        if (rootLevel >= 0 && (all || rootVisible[j])) {
            const VaLodLevel& lv = t.rootGeometry().levels()[static_cast<std::size_t>(rootLevel)];
            if (lv.drawable && lv.skin >= 0) {
                const Skin& skin = t.skins()[static_cast<std::size_t>(lv.skin)];
                emit(*lv.drawable, &skls, static_cast<std::uint32_t>(n), rootLevel,
                     detail::skinPaletteOf(crowd_, t, skin, std::span<const Affine>(model_.data() + base, n), active, nodeOps),
                     skin.joints.size());
            } else if (lv.drawable) {
                emit(*lv.drawable, &skls, static_cast<std::uint32_t>(n), rootLevel);
            }
        }
        const auto tnodes = t.nodes();
        for (std::size_t i = 0; i < n; ++i) {
            if (!active[i]) {
                i = t.subtreeEnd(i) - 1;
                continue;
            }
            if (!all && !visible[base + i]) continue;
            const int level = tnodes[i].geometry.selectSquared(d2);
            if (level < 0) continue;
            const auto& d = tnodes[i].geometry.levels()[static_cast<std::size_t>(level)].drawable;
            if (!d) continue;
            emit(*d, arena.push(composeAffine(skls, model_[base + i].toDMat4(), nodeOps)), static_cast<std::uint32_t>(i), level);
        }
        if (s.held[id] >= 0) {
            const auto& held = s.heldObjects[static_cast<std::size_t>(s.held[id])];
            for (std::uint32_t k = 0; k < held.size(); ++k) {
                const int holder = holderNode(t, active, held[k].node);
                const Mat4 world = holder < 0 ? skls : composeAffine(skls, model_[base + static_cast<std::size_t>(holder)].toDMat4(), nodeOps);
                if (!all) {
                    if (holder >= 0 && masks_[base + static_cast<std::size_t>(holder)] == kCulled) continue;
                    PlaneMask m = holder < 0 ? cand.mask : masks_[base + static_cast<std::size_t>(holder)];
                    ++stats_.spheresTested;
                    if (frustum.classify(held[k].drawable->localBound().transformed(world), m) == Containment::Outside) continue;
                }
                emit(*held[k].drawable, arena.push(world), static_cast<std::uint32_t>(n + 1 + k), 0);
            }
        }
    }
    stats_.drawListMs = watch.elapsedMs();
    stats_.fmultTotal = c ? counterRef.totalFmult() : 0;

    if (backend) {
        watch.restart();
        backend->beginFrame(camera);
        backend->draw(drawList_);
        backend->endFrame();
        stats_.drawMs = watch.elapsedMs();
    }
}

}  // namespace throng
