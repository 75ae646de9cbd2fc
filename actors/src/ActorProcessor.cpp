#include "throng/actors/ActorProcessor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cascade/CascadeFrame.h"
#include "throng/actors/cascade/BehavioursJob.h"
#include "throng/actors/cascade/DrawListJob.h"
#include "throng/actors/cascade/InternalCullingJob.h"
#include "throng/actors/cascade/ReferencePointsJob.h"
#include "throng/actors/cascade/RefpointPlacementJob.h"
#include "throng/actors/cascade/SkeletalLodJob.h"
#include "throng/actors/cascade/SkeletonRootCullingJob.h"
#include "throng/actors/cascade/SkeletonRootsJob.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/scenegraph/AppVisitor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/CullVisitor.h"
#include "throng/scenegraph/DrawBackend.h"
#include "throng/scenegraph/MatrixBoundsVisitor.h"
#include "throng/scenegraph/Node.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/scenegraph/ThreadTeam.h"
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

// Runs `work` and adds its milliseconds to `ms`.
template <class Work>
void timed(double& ms, Work&& work) {
    Stopwatch watch;
    work();
    ms += watch.elapsedMs();
}

// Each node's present members from phase 1's lists of the actors shown (membersListed frames).
void listPresentMembers(cascade::CascadeFrame& f, const Crowd::State& s) {
    // Node by node in member order (as a pass over the node's members would list them): counted,
    // placed, then sorted where the actors came out of order.
    f.listedOf.clear();
    const Node* last = nullptr;
    cascade::PresentMembers* entry = nullptr;
    auto entryOf = [&](const Node* node) -> cascade::PresentMembers& {
        if (node != last) entry = &f.listedOf[node], entry->node = node, last = node;
        return *entry;
    };
    for (const ActorId id : f.listed.shown)
        if (s.owner[id]) ++entryOf(s.owner[id]).count;
    std::size_t total = 0;
    for (auto& [node, e] : f.listedOf) e.first = total, total += e.count, e.count = 0;
    f.presentMembers.resize(total);
    f.listedIds.resize(total);
    last = nullptr;
    for (const ActorId id : f.listed.shown) {
        if (!s.owner[id]) continue;
        cascade::PresentMembers& e = entryOf(s.owner[id]);
        const std::size_t k = e.first + e.count++;
        f.presentMembers[k] = s.member[id];
        f.listedIds[k] = id;
    }
    for (const auto& [node, e] : f.listedOf) {
        const auto members = f.presentMembers.begin() + std::ptrdiff_t(e.first);
        if (std::is_sorted(members, members + std::ptrdiff_t(e.count))) continue;
        f.presentIds.resize(e.count);
        std::vector<std::size_t> order(e.count);  // rare: actors numbered against their members' order
        for (std::size_t k = 0; k < e.count; ++k) order[k] = k;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return members[std::ptrdiff_t(a)] < members[std::ptrdiff_t(b)]; });
        std::vector<std::uint32_t> sortedMembers(e.count);
        for (std::size_t k = 0; k < e.count; ++k)
            sortedMembers[k] = members[std::ptrdiff_t(order[k])], f.presentIds[k] = f.listedIds[e.first + order[k]];
        std::copy(sortedMembers.begin(), sortedMembers.end(), members);
        std::copy(f.presentIds.begin(), f.presentIds.end(), f.listedIds.begin() + std::ptrdiff_t(e.first));
    }
}

}  // namespace

ActorProcessor::ActorProcessor(Crowd& crowd)
    : crowd_(crowd), team_(std::make_unique<ThreadTeam>(1)), cascade_(std::make_unique<cascade::CascadeFrame>()) {}

ActorProcessor::~ActorProcessor() = default;

void ActorProcessor::setLodScale(double scale) {
    traditional_.setLodScale(scale);  // validates
    lodScale_ = scale;
}

void ActorProcessor::setOcclusion(const std::optional<OcclusionSettings>& settings) {
    traditional_.setOcclusion(settings);  // validates
    if (settings) occlusion_.emplace(*settings);
    else occlusion_.reset();
}

void ActorProcessor::setCullingFrustum(std::optional<Frustum> frustum) {
    traditional_.setCullingFrustum(frustum);
    cullingFrustum_ = frustum;
}

void ActorProcessor::setThreads(unsigned threads) {
    if (threads == 0) throw std::invalid_argument("ActorProcessor::setThreads: argument 'threads' must be at least 1");
    team_ = std::make_unique<ThreadTeam>(threads);
}

unsigned ActorProcessor::threads() const { return team_->threads(); }

void ActorProcessor::setImpostorDistance(double distance, double hysteresis) {
    if (!(distance >= 0.0) || !std::isfinite(distance) || !(hysteresis >= 0.0) || !std::isfinite(hysteresis))
        throw std::invalid_argument("ActorProcessor::setImpostorDistance: distance and hysteresis must be finite and >= 0");
    impostorDistance_ = distance;
    impostorHysteresis_ = hysteresis;
    if (distance == 0.0) impostorTier_.clear();
}

void ActorProcessor::setKeyPoseDistance(double distance, double hysteresis) {
    if (!(distance >= 0.0) || !std::isfinite(distance) || !(hysteresis >= 0.0) || !std::isfinite(hysteresis))
        throw std::invalid_argument("ActorProcessor::setKeyPoseDistance: distance and hysteresis must be finite and >= 0");
    keyPoseDistance_ = distance;
    keyPoseHysteresis_ = hysteresis;
    if (distance == 0.0) keyPoseTier_.clear();
}

void ActorProcessor::setTiers(ActorId id, ActorTiers tiers) {
    if (id >= crowd_.size())
        throw std::invalid_argument("ActorProcessor::setTiers: actor " + std::to_string(id) + " does not exist (" +
                                    std::to_string(crowd_.size()) + " actors)");
    if (tiers.impostor > 1 || tiers.keyPose > 1) throw std::invalid_argument("ActorProcessor::setTiers: a tier is 0 or 1");
    // Sized as CULL 2 sizes them (every actor), so that the job finds them as it left them.
    if (impostorTier_.size() < crowd_.size()) impostorTier_.resize(crowd_.size(), 0);
    if (keyPoseTier_.size() < crowd_.size()) keyPoseTier_.resize(crowd_.size(), 0);
    impostorTier_[id] = tiers.impostor;
    keyPoseTier_[id] = tiers.keyPose;
}

void ActorProcessor::setKeyPoseCache(std::shared_ptr<KeyPoseCache> cache) {
    if (!cache) throw std::invalid_argument("ActorProcessor::setKeyPoseCache: argument 'cache' is null");
    std::erase_if(keyPoseCaches_, [&](const auto& c) { return &c->actorTemplate() == &cache->actorTemplate(); });
    keyPoseCaches_.push_back(std::move(cache));
}

void ActorProcessor::clearKeyPoseCaches() { keyPoseCaches_.clear(); }

void ActorProcessor::setImpostor(const ActorTemplate& tmpl, std::shared_ptr<const Drawable> impostor) {
    std::erase_if(impostors_, [&](const auto& e) { return e.first == &tmpl; });
    if (impostor) impostors_.emplace_back(&tmpl, std::move(impostor));
}

const DrawList& ActorProcessor::drawList() const {
    return stats_.processing == Processing::Traditional ? traditional_.drawList() : drawLists_[current_];
}

const ActorFrameStatistics& ActorProcessor::processFrame(Node& root, const Camera& camera, double time,
                                                         DrawBackend* backend) {
    requireFinite(time, "ActorProcessor::processFrame", "time");
    team_->run([&] {
        if (processing_ == Processing::Actor) processActors(root, camera, time);
        else processTraditionally(root, camera, time);
    });
    if (backend) timed(stats_.drawMs, [&] { backend->drawFrame(camera, drawList()); });
    lastTime_ = time;
    ++frame_;
    return stats_;
}

void ActorProcessor::processTraditionally(Node& root, const Camera& camera, double time) {
    const FrameStatistics& f = traditional_.processFrame(root, camera, time);
    stats_ = ActorFrameStatistics{};
    stats_.processing = Processing::Traditional;
    stats_.frame = frame_;
    stats_.appMs = f.appMs;
    stats_.matricesBoundsMs = f.matricesBoundsMs;
    stats_.cullMs = f.cullMs;
    const Crowd::State& s = crowd_.state();
    for (std::size_t id = 0; id < crowd_.size(); ++id)
        if (s.owner[id]) {
            ++stats_.actorsInScene;
            stats_.skeletonNodesEvaluated += s.tmpl[id]->nodeCount();
        }
    stats_.actorsPosed = stats_.actorsInScene;
    stats_.internalSpheresComputed = f.matrices.spheresRecomputed;
    stats_.nodesOccluded = f.cull.nodesOccluded;
    stats_.occlusionTests = stats_.occlusionObjectsTested = f.cull.occlusionTests;
    stats_.occludersDrawn = f.occlusion.occludersDrawn;
    stats_.occlusionBufferMs = f.occlusion.bufferMs;
    stats_.occlusionRested = f.occlusion.rested;
    stats_.spheresTested = f.cull.spheresTested;
    stats_.lodDistances = f.cull.lodDistances;
    stats_.drawItems = f.cull.drawItems;
    stats_.primitives = f.cull.primitives;
    stats_.fmultTotal = f.fmultTotal;
}

// The seven phases of seed 002 §4.2, top to bottom; the generic traversals take the scene's other
// nodes through APP, matrices and bounds, and CULL, and hand actor nodes to the cascade.
void ActorProcessor::processActors(Node& root, const Camera& camera, double time) {
    OpCounter& counter = this->counter();
    counter.reset();
    OpCounter* c = counter.enabled() ? &counter : nullptr;
    stats_ = ActorFrameStatistics{};
    stats_.processing = Processing::Actor;
    stats_.frame = frame_;
    current_ = 1 - current_;  // the previous frame's list stays intact for a DRAW still reading it
    DrawList& list = drawLists_[current_];
    list.clear();

    cascade::CascadeFrame& f = *cascade_;
    f.frustum = cullingFrustum_ ? *cullingFrustum_ : camera.frustum();
    f.eye = camera.eye();
    f.context = FrameContext{time, frame_ == 0 ? 0.0 : time - lastTime_, frame_, c};
    f.settings = cascade::Settings{lodScale_ * lodScale_, skeletalLod_,           behaviouralLod_,    impostorDistance_,
                                   impostorHysteresis_,   &impostors_,            keyPoseDistance_,   keyPoseHysteresis_,
                                   &keyPoseCaches_};
    f.loop.begin(stats_, c, &list);
    f.candidates.clear();
    f.presentMembers.clear(), f.presentOf.clear(), f.presentCursor = 0;
    f.occlusion = nullptr;
    Crowd::State& s = crowd_.state();

    // Generic APP: update callbacks of generic nodes (actor nodes wait for phase 1).
    timed(stats_.appMs, [&] {
        WithActorTraversal<AppVisitor> app(this, f.context);
        root.accept(app);
    });
    // Phase 1: every actor's Reference Point; the generic matrices traversal places them in the
    // world (bound() below, a RefpointPlacementJob per actor node).
    timed(stats_.refpointMs, [&] {
        cascade::ReferencePointsJob{&crowd_, f.context, &f.listed}.run(f.loop);
        f.membersListed = f.listed.active;
        if (f.membersListed) listPresentMembers(f, s);
    });
    timed(stats_.matricesBoundsMs, [&] {
        WithActorTraversal<MatrixBoundsVisitor> matrices(this, c, false);
        root.accept(matrices);
        stats_.internalSpheresComputed += matrices.statistics().spheresRecomputed;
    });
    // Occlusion, when on: this frame's occluders drawn into the buffer CULL tests against.
    // A stage that rests this frame (the last one rejected little) builds and tests nothing.
    if (sharedOcclusion_) {
        f.occlusion = sharedOcclusion_;  // drawn by another process for this frame
    } else if (occlusion_ && occlusion_->due(camera)) {
        const OcclusionStatistics& o = occlusion_->build(root, camera, f.frustum);
        stats_.occlusionBufferMs = o.bufferMs;
        stats_.occludersDrawn = o.occludersDrawn;
        f.occlusion = &occlusion_->buffer();
    }
    stats_.occlusionRested = occlusion_ && occlusion_->statistics().rested;
    occlusionBuilt_ = f.occlusion && !sharedOcclusion_;
    if (beforeCull_) beforeCull_(f.occlusion);
    // Generic CULL, which meets actor nodes after the generic groups above them (cull() below
    // gathers the candidates); phase 2: CULL 1, then occlusion of the survivors.
    timed(stats_.cullMs, [&] {
        WithActorTraversal<CullVisitor> cull(this, camera, list, c, lodScale_);
        if (cullingFrustum_) cull.setCullingFrustum(*cullingFrustum_);
        cull.setFrameTime(time);
        cull.setOcclusion(f.occlusion);
        root.accept(cull);
        // One node per test, and the actors rejected with their group's sphere as tested with it. A
        // process testing against another's buffer holds the same nodes: they count there, once.
        if (!sharedOcclusion_) {
            stats_.nodesOccluded += cull.statistics().nodesOccluded;
            stats_.occlusionTests += cull.statistics().occlusionTests;
            stats_.occlusionObjectsTested += cull.statistics().occlusionTests;
        }
        stats_.occlusionObjectsTested += stats_.occludedWithGroup;
        stats_.spheresTested += cull.statistics().spheresTested;
        stats_.lodDistances += cull.statistics().lodDistances;
        stats_.drawItems += cull.statistics().drawItems;
        stats_.primitives += cull.statistics().primitives;
        cascade::RefpointCullingJob{&s, &f.frustum, f.eye, f.candidates, &f.survivors, s.actorClass, &f.cullScratch}.run(f.loop);
    });
    stats_.culledWithGroup = stats_.actorsInScene - f.candidates.size() - stats_.occludedWithGroup -
                             (stats_.a - (f.candidates.size() - f.survivors.size()));
    timed(stats_.refpointOcclusionMs, [&] {
        cascade::RefpointOcclusionJob{&s, f.occlusion, f.candidates, &f.survivors, s.actorClass, &f.occlusionScratch}.run(f.loop);
    });
    // Phase 3.
    timed(stats_.skeletonRootMs, [&] {
        cascade::SkeletonRootsJob{&s,     f.candidates,           f.survivors,         f.eye, time, f.settings.behaviouralLod,
                                  f.settings.lodScale2, s.root, s.sklsWorld}
            .run(f.loop);
    });
    // Phase 4: CULL 2, the key-pose caches' poses for the frame, skeletal LOD.
    timed(stats_.cull2Ms, [&] {
        cascade::SkeletonRootCullingJob{&s,          &f.frustum,    f.eye,         time,         &f.settings,
                                        f.occlusion, f.candidates,  f.survivors,   &impostorTier_, &keyPoseTier_,
                                        s.actorClass, s.eyeDistance, &f.decisions}
            .run(f.loop);
        if (f.settings.keyPoseCachesOn())
            timed(stats_.keyPoseSelectMs,
                  [&] { cascade::KeyPoseSelectingJob{&keyPoseCaches_, frame_, &f.decisions, &f.keyPoseScratch, keyPoseArbiter_}.run(f.loop); });
        cascade::SkeletalLodJob{&s, f.candidates, f.survivors, &f.decisions, skeletalLod_, &f.posed}.run(f.loop);
    });
    // Phase 5.
    timed(stats_.poseMs, [&] { cascade::BehavioursJob{&s, f.candidates, f.survivors, time, &f.posed, s.dofs}.run(f.loop); });
    // Phase 6: CULL 3.
    timed(stats_.cull3Ms, [&] {
        cascade::InternalCullingJob{&s, &f.frustum, f.candidates, f.survivors, &f.decisions, &f.posed, s.actorClass, &f.visibility}
            .run(f.loop);
    });
    // Phase 7.
    timed(stats_.drawListMs, [&] {
        cascade::DrawListJob{&s, &f.frustum, time, &f.settings, f.candidates, f.survivors, &f.decisions, &f.posed, &f.visibility}
            .run(f.loop);
    });
    if (occlusionBuilt_ && !occlusionByShares_) settleOcclusion(stats_);
    stats_.fmultTotal = c ? counter.totalFmult() : 0;
}

void ActorProcessor::settleOcclusion(const ActorFrameStatistics& whole) {
    if (!occlusionBuilt_) return;
    occlusion_->settle(whole.occludedWithGroup + whole.occludedRefpoint + whole.occludedSklsroot + whole.nodesOccluded,
                       whole.occlusionObjectsTested);
    occlusionBuilt_ = false;  // once per frame built
}

BoundingSphere ActorProcessor::bound(Node& node, std::span<const ActorId> ids, MatrixBoundsVisitor& visitor,
                                     const BoundingSphere& roaming) {
    visitor.statistics().worldMatricesComposed += ids.size();
    visitor.statistics().spheresRecomputed += ids.size();
    Crowd::State& s = crowd_.state();
    std::span<const ActorId> placed = ids;
    if (cascade_->membersListed) {
        // The present members as phase 1's lists found them (no pass over the node's members).
        cascade::CascadeFrame& f = *cascade_;
        const auto at = f.listedOf.find(&node);
        const cascade::PresentMembers present = at == f.listedOf.end() ? cascade::PresentMembers{&node, 0, 0} : at->second;
        f.presentOf.push_back(present);
        placed = std::span<const ActorId>(f.listedIds).subspan(present.first, present.count);
    } else if (stats_.actorsAbsent > 0) {
        // Only the present are placed (the others are stale here and widen no bound), and only they
        // become candidates of CULL 1 (cull() below takes this node's list). No branch per member:
        // who is present is random.
        cascade::CascadeFrame& f = *cascade_;
        const std::size_t first = f.presentMembers.size();
        f.presentMembers.resize(first + ids.size());
        f.presentIds.resize(ids.size());
        std::size_t n = 0;
        for (std::uint32_t member = 0; member < ids.size(); ++member) {
            const ActorId id = ids[member];
            f.presentMembers[first + n] = member, f.presentIds[n] = id;
            n += s.present[id] != 0;
        }
        f.presentMembers.resize(first + n);
        f.presentOf.push_back({&node, first, n});
        placed = std::span<const ActorId>(f.presentIds).first(n);
    }
    return cascade::RefpointPlacementJob{&s, placed, visitor.parentWorld(), visitor.parentIsIdentity(), roaming, s.refWorld,
                                         s.refSphereWorld}
        .run(cascade_->loop);
}

void ActorProcessor::cull(Node& node, std::span<const ActorId> ids, CullVisitor& visitor, bool boundIsMemberSphere) {
    const PlaneMask mask = visitor.planeMask();
    // A lone actor's node bound is its Refpoint Bsphere, which the traversal just tested (CULL 1);
    // a group's members are decided when they are inside every plane the group crosses.
    const bool decided = boundIsMemberSphere || mask == 0;
    const std::uint8_t stage = !decided ? cascade::kPending : mask == 0 ? cascade::kInside : cascade::kCrossing;
    // An actor absent here (another process simulates it and did not send it, or shows it itself)
    // is rejected unread (phase 1 classed and counted it A), so that CULL costs what this process
    // shows. bound() listed this node's present members.
    cascade::CascadeFrame& f = *cascade_;
    if (stats_.actorsAbsent == 0) {
        for (std::uint32_t member = 0; member < ids.size(); ++member)
            f.candidates.push_back(cascade::Candidate{ids[member], &node, member, mask, stage});
        return;
    }
    const cascade::PresentMembers& present = presentMembersOf(node);
    for (std::size_t k = present.first; k < present.first + present.count; ++k) {
        const std::uint32_t member = f.presentMembers[k];
        f.candidates.push_back(cascade::Candidate{ids[member], &node, member, mask, stage});
    }
}

void ActorProcessor::culledOut(Node& node, std::span<const ActorId> ids, CullVisitor& visitor) {
    // Every Refpoint Bsphere lies inside the node's bound, so every one is outside (or hidden) too.
    // The absent were classed and counted A in phase 1.
    Crowd::State& s = crowd_.state();
    const ActorClass why = visitor.rejectedByOcclusion() ? ActorClass::Occluded : ActorClass::A;
    std::uint64_t& count = why == ActorClass::A ? stats_.a : stats_.occludedWithGroup;
    if (stats_.actorsAbsent == 0) {
        for (ActorId id : ids) s.actorClass[id] = why;
        count += ids.size();
        return;
    }
    const cascade::CascadeFrame& f = *cascade_;
    const cascade::PresentMembers& present = presentMembersOf(node);
    for (std::size_t k = present.first; k < present.first + present.count; ++k) s.actorClass[ids[f.presentMembers[k]]] = why;
    count += present.count;
}

const cascade::PresentMembers& ActorProcessor::presentMembersOf(const Node& node) {
    // CULL meets the nodes in the order bound() met them, but for those culled with a group above.
    cascade::CascadeFrame& f = *cascade_;
    while (f.presentCursor < f.presentOf.size() && f.presentOf[f.presentCursor].node != &node) ++f.presentCursor;
    if (f.presentCursor == f.presentOf.size())
        throw std::logic_error("ActorProcessor: CULL met an actor node that the matrices traversal did not place");
    return f.presentOf[f.presentCursor++];
}

}  // namespace throng
