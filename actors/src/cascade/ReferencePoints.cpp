// Phase 1 of actor processing: Reference Points of every actor (simulation state, computed whatever
// the camera), and their placement in the world with their Refpoint Bspheres.

#include <limits>

#include "../ReferencePointRuns.h"
#include "CascadeFrame.h"
#include "throng/actors/Crowd.h"
#include "throng/scenegraph/Transform.h"
#include "throng/scenegraph/Node.h"

namespace throng::cascade {

void computeReferencePoints(CascadeFrame& f) {
    Crowd::State& s = f.crowd->state();
    f.parallel(f.crowd->size(), kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        FrameContext context = f.context;
        context.counter = f.counterOf(out);
        OpTally* ops = tallyFor(context.counter, OpCategory::RefpointDofValues);
        detail::computeReferencePointRuns(s, begin, end, [](std::size_t id) { return ActorId(id); }, context, ops);
        for (std::size_t id = begin; id < end; ++id) {
            s.eyeDistance[id] = std::numeric_limits<double>::infinity();
            const bool inScene = s.owner[id] != nullptr;
            s.actorClass[id] = inScene ? ActorClass::CulledWithGroup : ActorClass::NotInScene;
            out.counts.actorsInScene += inScene;
        }
    });
    for (Node* node : f.crowd->nodes()) node->dirtyBound();  // every actor moved
}

namespace {

// Places members [begin, end) of `ids` and grows `bound` over their Refpoint Bspheres (see
// placeReferencePoints), with their costs in `c` (null when not counting).
void placeRange(Crowd::State& s, std::span<const ActorId> ids, std::size_t begin, std::size_t end, const Mat4& parent,
                bool parentIsIdentity, const BoundingSphere& roaming, BoundingSphere& bound, OpCounter* c) {
    const bool group = ids.size() > 1;
    const bool grow = !roaming.valid();
    OpTally* refOps = tallyFor(c, OpCategory::RefpointMatrix);
    OpTally* sphereOps = tallyFor(c, OpCategory::BsphereRecompute);
    for (std::size_t k = begin; k < end; ++k) {
        const ActorId id = ids[k];
        s.refWorld[id] = parentIsIdentity ? s.refLocal[id] : composeAffine(parent, s.refLocal[id], refOps);
        s.refSphereWorld[id] = s.refSphereLocal[id].transformed(s.refWorld[id], sphereOps);
        if (!grow) {  // a declared roaming bound: only a member outside it (never, if it holds) widens it
            if (!roaming.clearlyContains(s.refSphereWorld[id]) && !roaming.contains(s.refSphereWorld[id]))
                bound.expandBy(s.refSphereWorld[id], group ? sphereOps : nullptr);
            continue;
        }
        // Most members lie well inside the bound grown so far: no square root for them (when
        // counting operations, every member goes through expandBy as the model prices it).
        if (sphereOps || !bound.clearlyContains(s.refSphereWorld[id]))
            bound.expandBy(s.refSphereWorld[id], group ? sphereOps : nullptr);
    }
    countOperations(c, OpCategory::RefpointMatrix, end - begin);
    countOperations(c, OpCategory::BsphereRecompute, end - begin);
}

}  // namespace

BoundingSphere placeReferencePoints(CascadeFrame& f, std::span<const ActorId> ids, const Mat4& parent, bool parentIsIdentity,
                                   const BoundingSphere& roaming) {
    Crowd::State& s = f.crowd->state();
    OpTally* sphereOps = tallyFor(f.context.counter, OpCategory::BsphereRecompute);
    BoundingSphere bound = roaming;
    if (ids.size() <= kLightGrain) {
        // One chunk (a town's small groups, a lone actor): the same work and the same merge as
        // below, without the chunk outputs a parallel loop needs.
        BoundingSphere grown;
        placeRange(s, ids, 0, ids.size(), parent, parentIsIdentity, roaming, grown, f.context.counter);
        bound.expandBy(grown, sphereOps);
        return bound;
    }
    f.parallel(ids.size(), kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        placeRange(s, ids, begin, end, parent, parentIsIdentity, roaming, out.bound, f.counterOf(out));
    });
    // The chunks' bounds, merged in chunk order (after the roaming bound, when declared).
    for (std::size_t c = 0; c < chunkCount(ids.size(), kLightGrain); ++c) bound.expandBy(f.chunks[c].bound, sphereOps);
    return bound;
}

}  // namespace throng::cascade
