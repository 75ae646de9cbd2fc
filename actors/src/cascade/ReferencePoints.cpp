// Phase 1 of actor processing: Reference Points of every actor (simulation state, computed whatever
// the camera), and their placement in the world with their Refpoint Bspheres.

#include <algorithm>
#include <limits>

#include "../ReferencePointRuns.h"
#include "throng/actors/cascade/ReferencePointsJob.h"
#include "throng/actors/cascade/RefpointPlacementJob.h"
#include "throng/scenegraph/Node.h"
#include "throng/scenegraph/Transform.h"

namespace throng::cascade {

const char* ReferencePointsJob::problem() const {
    if (!crowd) return "no crowd";
    return nullptr;
}

namespace {

// Whether some behaviour of `crowd` lists its present slots this frame.
bool someBehaviourLists(const Crowd& crowd) {
    for (const auto& b : crowd.behaviours())
        if (b->presentSlots()) return true;
    return false;
}

// The class of an actor after phase 1.
ActorClass classAfterPhase1(const Crowd::State& s, ActorId id) {
    return !s.owner[id] ? ActorClass::NotInScene : s.present[id] ? ActorClass::CulledWithGroup : ActorClass::A;
}

}  // namespace

void ReferencePointsJob::run(PhaseLoop& loop) const {
    throwIfInvalid("ReferencePointsJob", loop.ready() ? problem() : "the loop has no frame");
    if (listed && someBehaviourLists(*crowd)) {
        runListed(loop);
        return;
    }
    if (listed) listed->active = false;
    crowd->writeAllStates();
    Crowd::State& s = crowd->state();
    loop.parallel(crowd->size(), kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        FrameContext chunkContext = context;
        chunkContext.counter = loop.counterOf(out);
        OpTally* ops = tallyFor(chunkContext.counter, OpCategory::RefpointDofValues);
        detail::computeReferencePointRuns(s, begin, end, [](std::size_t id) { return ActorId(id); }, chunkContext, ops);
        for (std::size_t id = begin; id < end; ++id) {
            s.eyeDistance[id] = std::numeric_limits<double>::infinity();
            const bool inScene = s.owner[id] != nullptr, present = s.present[id] != 0;
            // An absent actor is rejected by CULL 1 unread, whatever its groups (see ActorProcessor::cull).
            s.actorClass[id] = !inScene ? ActorClass::NotInScene : present ? ActorClass::CulledWithGroup : ActorClass::A;
            out.counts.actorsInScene += inScene;
            out.counts.actorsAbsent += inScene && !present;
            out.counts.a += inScene && !present;
        }
    });
    for (Node* node : crowd->nodes()) node->dirtyBound();  // every actor moved
}

void ReferencePointsJob::runListed(PhaseLoop& loop) const {
    Crowd::State& s = crowd->state();
    Listed& l = *listed;
    if (!l.active) {  // from visiting every actor: every one absent until visited
        for (ActorId id = 0; id < crowd->size(); ++id) {
            s.present[id] = 0;
            s.eyeDistance[id] = std::numeric_limits<double>::infinity();
            s.actorClass[id] = classAfterPhase1(s, id);
        }
        l.shown.clear();
        l.active = true;
    }
    for (const ActorId id : l.shown) s.present[id] = 0;
    // The listed actors, and every actor of the behaviours that list none, behaviour by behaviour
    // (computeReferencePointRuns takes runs of one behaviour).
    l.visit.clear();
    l.listing.clear();
    for (std::size_t b = 0; b < crowd->behaviours().size(); ++b) {
        const std::span<const ActorId> bySlot = crowd->actorsBySlot(b);
        if (const auto slots = crowd->behaviours()[b]->presentSlots()) {
            l.listing.push_back(crowd->behaviours()[b].get());
            for (const std::uint32_t slot : *slots)
                if (slot < bySlot.size() && bySlot[slot] != kNoActor) l.visit.push_back(bySlot[slot]);
        } else {
            for (const ActorId id : bySlot)
                if (id != kNoActor) l.visit.push_back(id);
        }
    }
    // Actors visited for the first time get the state they deferred (Crowd::deferStateUntilShown).
    if (crowd->deferredStates() > 0)
        for (const ActorId id : l.visit) crowd->writeState(id);
    loop.parallel(l.visit.size(), kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        FrameContext chunkContext = context;
        chunkContext.counter = loop.counterOf(out);
        OpTally* ops = tallyFor(chunkContext.counter, OpCategory::RefpointDofValues);
        detail::computeReferencePointRuns(s, begin, end, [&](std::size_t k) { return l.visit[k]; }, chunkContext, ops,
                                          [&](const Behaviour* b) { return std::find(l.listing.begin(), l.listing.end(), b) != l.listing.end(); });
        for (std::size_t k = begin; k < end; ++k) {
            const ActorId id = l.visit[k];
            s.eyeDistance[id] = std::numeric_limits<double>::infinity();
            s.actorClass[id] = classAfterPhase1(s, id);
        }
    });
    // Those shown last frame and not now, and who is shown now.
    for (const ActorId id : l.shown)
        if (!s.present[id]) s.eyeDistance[id] = std::numeric_limits<double>::infinity(), s.actorClass[id] = classAfterPhase1(s, id);
    l.shown.clear();
    std::uint64_t shownInScene = 0;
    for (const ActorId id : l.visit)
        if (s.present[id]) l.shown.push_back(id), shownInScene += s.owner[id] != nullptr;
    ActorFrameStatistics& stats = loop.statistics();
    const std::uint64_t inScene = crowd->actorsInScene();
    stats.actorsInScene += inScene;
    stats.actorsAbsent += inScene - shownInScene;
    stats.a += inScene - shownInScene;
    for (Node* node : crowd->nodes()) node->dirtyBound();  // every actor moved
}

namespace {

// Places members [begin, end) of the job's actors and grows `bound` over their Refpoint Bspheres
// (see RefpointPlacementJob::run), with their costs in `c` (null when not counting).
void placeRange(const RefpointPlacementJob& job, std::size_t begin, std::size_t end, BoundingSphere& bound, OpCounter* c) {
    const Crowd::State& s = *job.crowd;
    const bool group = job.ids.size() > 1;
    const bool grow = !job.roaming.valid();
    OpTally* refOps = tallyFor(c, OpCategory::RefpointMatrix);
    OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
    for (std::size_t k = begin; k < end; ++k) {
        const ActorId id = job.ids[k];
        const Mat4& world = job.refWorld[id] = job.parentIsIdentity ? s.refLocal[id] : composeAffine(job.parent, s.refLocal[id], refOps);
        const BoundingSphere& sphere = job.refSphereWorld[id] = s.refSphereLocal[id].transformed(world, sphereOps);
        if (!grow) {  // a declared roaming bound: only a member outside it (never, if it holds) widens it
            if (!job.roaming.clearlyContains(sphere) && !job.roaming.contains(sphere)) bound.expandBy(sphere, group ? sphereOps : nullptr);
            continue;
        }
        // Most members lie well inside the bound grown so far: no square root for them (when
        // counting operations, every member goes through expandBy as the model prices it).
        if (sphereOps || !bound.clearlyContains(sphere)) bound.expandBy(sphere, group ? sphereOps : nullptr);
    }
    countOperations(c, OpCategory::RefpointMatrix, end - begin);
    countOperations(c, OpCategory::BsphereRecompute, end - begin);
}

}  // namespace

const char* RefpointPlacementJob::problem() const {
    if (!crowd) return "no crowd";
    const std::size_t n = crowd->tmpl.size();
    if (refWorld.size() != n || refSphereWorld.size() != n) return "refWorld and refSphereWorld must have one entry per actor";
    return nullptr;
}

BoundingSphere RefpointPlacementJob::run(PhaseLoop& loop) const {
    throwIfInvalid("RefpointPlacementJob", loop.ready() ? problem() : "the loop has no frame");
    OpTally* sphereOps = tallyFor(loop.counter(), OpCategory::BsphereRecompute);
    BoundingSphere bound = roaming;
    if (ids.size() <= kLightGrain) {
        // One chunk (a town's small groups, a lone actor): the same work and the same merge as
        // below, without the chunk outputs a parallel loop needs.
        BoundingSphere grown;
        placeRange(*this, 0, ids.size(), grown, loop.counter());
        bound.expandBy(grown, sphereOps);
        return bound;
    }
    loop.parallel(ids.size(), kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        placeRange(*this, begin, end, out.bound, loop.counterOf(out));
    });
    // The chunks' bounds, merged in chunk order (after the roaming bound, when declared).
    for (std::size_t c = 0; c < chunkCount(ids.size(), kLightGrain); ++c) bound.expandBy(loop.chunk(c).bound, sphereOps);
    return bound;
}

}  // namespace throng::cascade
