// Phase 3 of actor processing: the Skeleton Roots of the actors that passed CULL 1.

#include <cmath>

#include "CascadeFrame.h"
#include "throng/actors/Crowd.h"
#include "throng/scenegraph/Transform.h"
#include "throng/actors/SkeletonPose.h"

namespace throng::cascade {

void computeSkeletonRoots(CascadeFrame& f) {
    Crowd::State& s = f.crowd->state();
    const double time = f.context.time;
    f.parallel(f.survivors.size(), kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        OpCounter* c = f.counterOf(out);
        OpTally* rootOps = tallyFor(c, OpCategory::SkeletonRootMatrix);
        OpTally* valueOps = tallyFor(c, OpCategory::SkeletonRootDofValues);
        for (std::size_t k = begin; k < end; ++k) {
            const ActorId id = f.candidates[f.survivors[k]].id;
            Behaviour& b = *s.behaviour[id];
            int level = 0;
            if (f.settings.behaviouralLod) {  // the Skeleton Root is not placed yet: judge by the Reference Point
                const Vec3 d = s.refSphereWorld[id].center() - f.eye;
                level = b.levelFor(std::sqrt(glm::dot(d, d) * f.settings.lodScale2) / s.priority[id]);
            }
            s.root[id] = b.skeletonRoot(s.slot[id], time, level, valueOps);
            s.sklsWorld[id] = composeAffine(s.refWorld[id], rootPoseMatrix(s.root[id], rootOps), rootOps);
        }
        countOperations(c, OpCategory::SkeletonRootMatrix, end - begin);
    });
}

}  // namespace throng::cascade
