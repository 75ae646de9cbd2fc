// The chunk outputs of the cascade's loops, how they join into the frame's, and the jobs' one error.

#include "throng/actors/cascade/PhaseLoop.h"

#include <stdexcept>
#include <string>

#include "throng/actors/cascade/CascadeTypes.h"

namespace throng::cascade {

void addCounts(ActorFrameStatistics& into, const ActorFrameStatistics& from) {
    into.actorsInScene += from.actorsInScene;
    into.actorsAbsent += from.actorsAbsent;
    into.culledWithGroup += from.culledWithGroup;
    into.a += from.a;
    into.b += from.b;
    into.c1 += from.c1;
    into.c2 += from.c2;
    into.c3_1 += from.c3_1;
    into.c3_2 += from.c3_2;
    into.occludedWithGroup += from.occludedWithGroup;
    into.occludedRefpoint += from.occludedRefpoint;
    into.occludedSklsroot += from.occludedSklsroot;
    into.occlusionCellsTested += from.occlusionCellsTested;
    into.occlusionCellsHidden += from.occlusionCellsHidden;
    into.occlusionTests += from.occlusionTests;
    into.occlusionObjectsTested += from.occlusionObjectsTested;
    into.nodesOccluded += from.nodesOccluded;
    into.occludersDrawn += from.occludersDrawn;
    into.actorsPosed += from.actorsPosed;
    into.impostors += from.impostors;
    into.keyPoseBand += from.keyPoseBand;
    into.keyPoseActors += from.keyPoseActors;
    into.keyPoseMisses += from.keyPoseMisses;
    into.keyPoseUpdates += from.keyPoseUpdates;
    into.keyPosesWanted += from.keyPosesWanted;
    into.keyPosesHeld += from.keyPosesHeld;
    into.skeletonNodesEvaluated += from.skeletonNodesEvaluated;
    into.internalSpheresComputed += from.internalSpheresComputed;
    into.spheresTested += from.spheresTested;
    into.lodDistances += from.lodDistances;
    into.eyeDistances += from.eyeDistances;
    into.drawItems += from.drawItems;
    into.primitives += from.primitives;
}

void PhaseLoop::prepareChunks(std::size_t count) {
    if (chunks_.size() < count) chunks_.resize(count);
    for (std::size_t c = 0; c < count; ++c) {
        ChunkOutput& out = chunks_[c];
        out.counts = ActorFrameStatistics{};
        // Tallies are only written while the frame counts (counterOf gives null otherwise).
        if (counter_) out.ops.reset();
        out.ops.setEnabled(counter_ != nullptr);
        out.items = nullptr;
        out.bound = BoundingSphere();
    }
}

void PhaseLoop::joinChunks(std::size_t count) {
    for (std::size_t c = 0; c < count; ++c) {
        addCounts(*stats_, chunks_[c].counts);
        if (counter_) counter_->add(chunks_[c].ops);
    }
}

void throwIfInvalid(const char* job, const char* problem) {
    if (problem) throw std::invalid_argument(std::string(job) + ": " + problem);
}

}  // namespace throng::cascade
