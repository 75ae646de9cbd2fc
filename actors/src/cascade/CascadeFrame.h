#pragma once
// Internal to actors: what the ActorProcessor keeps from frame to frame for the cascade's jobs (the
// values they pass each other, their scratch, the chunk outputs), so a warm frame allocates nothing.
// The jobs themselves (throng/actors/cascade/) declare what each reads and writes.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/KeyPoseSelectingJob.h"
#include "throng/actors/cascade/PhaseLoop.h"
#include "throng/actors/cascade/ReferencePointsJob.h"
#include "throng/actors/cascade/RefpointCullingJob.h"
#include "throng/actors/cascade/RefpointOcclusionJob.h"
#include "throng/scenegraph/FrameContext.h"
#include "throng/scenegraph/Frustum.h"

namespace throng {
class OcclusionBuffer;
}

namespace throng::cascade {

/// The present members of one actor node (see CascadeFrame::presentMembers).
struct PresentMembers {
    const Node* node = nullptr;  ///< the node
    std::size_t first = 0;       ///< its first entry in presentMembers
    std::size_t count = 0;       ///< how many
};

/// The cascade's state between its jobs, reused from frame to frame.
struct CascadeFrame {
    // The frame.
    Frustum frustum;                             ///< the culling frustum
    Vec3 eye{0.0};                               ///< the eye
    FrameContext context;                        ///< time, frame number, counter (null when not counting)
    Settings settings;                           ///< LOD, impostor and key-pose settings
    const OcclusionBuffer* occlusion = nullptr;  ///< this frame's occluders, or null: no occlusion

    // What the jobs pass each other, and their workspaces.
    PhaseLoop loop;                              ///< the chunked loops of every job
    std::vector<Candidate> candidates;           ///< actors reaching CULL 1 (from the generic CULL)
    // When some actors are absent (simulated elsewhere), the present members of each actor node
    // as the matrices traversal placed them, for CULL to take as its candidates.
    std::vector<std::uint32_t> presentMembers;   ///< member indices, node after node
    std::vector<PresentMembers> presentOf;       ///< each node's stretch of presentMembers, in traversal order
    std::size_t presentCursor = 0;               ///< CULL's place in presentOf
    std::vector<ActorId> presentIds;             ///< scratch: the present members of the node being placed
    // When a behaviour lists its present slots (phase 1's `listed`), the present members of every
    // node are found from the actors shown, not by a pass over each node's members.
    ReferencePointsJob::Listed listed;           ///< phase 1's lists, kept between frames
    bool membersListed = false;                  ///< this frame's present members come from listed.shown
    std::unordered_map<const Node*, PresentMembers> listedOf;  ///< per node: its stretch of presentMembers and listedIds
    std::vector<ActorId> listedIds;              ///< the actors of presentMembers, when listed
    std::vector<std::uint32_t> survivors;        ///< candidate indices past CULL 1 and occlusion
    SurvivorDecisions decisions;                 ///< CULL 2's, per survivor
    PosedActors posed;                           ///< the actors shown and posed
    InternalVisibility visibility;               ///< CULL 3's
    RefpointCullingJob::Scratch cullScratch;     ///< CULL 1's flat sphere arrays
    RefpointOcclusionJob::Scratch occlusionScratch;  ///< the occlusion cells
    KeyPoseSelectingJob::Scratch keyPoseScratch;     ///< the key-pose selection's workspace
};

}  // namespace throng::cascade
