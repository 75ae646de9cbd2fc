#include "CascadeFrame.h"

namespace throng::cascade {

void addCounts(ActorFrameStatistics& into, const ActorFrameStatistics& from) {
    into.actorsInScene += from.actorsInScene;
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

void CascadeFrame::prepareChunks(std::size_t count) {
    if (chunks.size() < count) chunks.resize(count);
    for (std::size_t c = 0; c < count; ++c) {
        ChunkOutput& out = chunks[c];
        out.counts = ActorFrameStatistics{};
        // Tallies are only written while the frame counts (counterOf gives null otherwise).
        if (context.counter) out.ops.reset();
        out.ops.setEnabled(context.counter != nullptr);
        out.items = nullptr;
        out.bound = BoundingSphere();
    }
}

void CascadeFrame::joinChunks(std::size_t count) {
    for (std::size_t c = 0; c < count; ++c) {
        addCounts(*stats, chunks[c].counts);
        if (context.counter) context.counter->add(chunks[c].ops);
    }
}

}  // namespace throng::cascade
