// Phase 1 of actor processing: Reference Points of every actor (simulation state, computed whatever
// the camera), and their placement in the world with their Refpoint Bspheres.

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

void ReferencePointsJob::run(PhaseLoop& loop) const {
    throwIfInvalid("ReferencePointsJob", loop.ready() ? problem() : "the loop has no frame");
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
