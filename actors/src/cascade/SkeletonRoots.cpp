// Phase 3 of actor processing: the Skeleton Roots of the actors that passed CULL 1.

#include <cmath>

#include "throng/actors/SkeletonPose.h"
#include "throng/actors/cascade/SkeletonRootsJob.h"
#include "throng/scenegraph/Transform.h"

namespace throng::cascade {

const char* SkeletonRootsJob::problem() const {
    if (!crowd) return "no crowd";
    const std::size_t n = crowd->tmpl.size();
    if (root.size() != n || sklsWorld.size() != n) return "root and sklsWorld must have one entry per actor";
    if (survivors.size() > candidates.size()) return "more survivors than candidates";
    return nullptr;
}

void SkeletonRootsJob::run(PhaseLoop& loop) const {
    throwIfInvalid("SkeletonRootsJob", loop.ready() ? problem() : "the loop has no frame");
    const Crowd::State& s = *crowd;
    loop.parallel(survivors.size(), kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        OpCounter* c = loop.counterOf(out);
        OpTally* rootOps = tallyFor(c, OpCategory::SkeletonRootMatrix);
        OpTally* valueOps = tallyFor(c, OpCategory::SkeletonRootDofValues);
        for (std::size_t k = begin; k < end; ++k) {
            const ActorId id = candidates[survivors[k]].id;
            Behaviour& b = *s.behaviour[id];
            int level = 0;
            if (behaviouralLod) {  // the Skeleton Root is not placed yet: judge by the Reference Point
                const Vec3 d = s.refSphereWorld[id].center() - eye;
                level = b.levelFor(std::sqrt(glm::dot(d, d) * lodScale2) / s.priority[id]);
            }
            root[id] = b.skeletonRoot(s.slot[id], time, level, valueOps);
            sklsWorld[id] = composeAffine(s.refWorld[id], rootPoseMatrix(root[id], rootOps), rootOps);
        }
        countOperations(c, OpCategory::SkeletonRootMatrix, end - begin);
    });
}

}  // namespace throng::cascade
