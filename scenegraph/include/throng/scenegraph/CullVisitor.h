#pragma once
// The CULL traversal of traditional processing: tests world bounds against the frustum with plane
// masks, lets every LOD node compute its own eye distance, and fills the draw list.

#include <cstdint>
#include <span>

#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/NodeVisitor.h"

namespace throng {

class Camera;
class OcclusionBuffer;
class OpCounter;

/// Work done and results of one CULL traversal.
struct CullStatistics {
    std::uint64_t nodesVisited = 0;    ///< nodes reached
    std::uint64_t spheresTested = 0;   ///< sphere-frustum tests (NO_04b)
    std::uint64_t nodesRejected = 0;   ///< nodes found outside (their subtrees skipped)
    std::uint64_t occlusionTests = 0;  ///< bounds tested against the occlusion buffer
    std::uint64_t nodesOccluded = 0;   ///< nodes found hidden by occluders (their subtrees skipped)
    std::uint64_t lodDistances = 0;    ///< eye distances computed by LOD nodes (NO_05)
    std::uint64_t drawItems = 0;       ///< items added to the draw list
    std::uint64_t primitives = 0;      ///< primitives of those items
};

/// Culls a tree whose world matrices and bounds are up to date.
class CullVisitor : public NodeVisitor {
public:
    /// Culls for `camera` into `drawList` (appending), accounting into `counter` (may be null).
    /// `lodScale` multiplies every LOD distance (> 1 lowers detail sooner).
    CullVisitor(const Camera& camera, DrawList& drawList, OpCounter* counter = nullptr, double lodScale = 1.0);

    /// Replaces the culling frustum (for example a smaller one, to watch culling at work).
    void setCullingFrustum(const Frustum& frustum);
    /// Also rejects nodes whose bound `buffer` finds hidden (null: no occlusion culling). The
    /// buffer must be finished for this camera and outlive the traversal.
    void setOcclusion(const OcclusionBuffer* buffer) { occlusion_ = buffer; }
    /// The occlusion buffer in use, or null.
    const OcclusionBuffer* occlusion() const { return occlusion_; }
    /// Sets the simulation time of the frame (draw items of animated nodes record what they show).
    void setFrameTime(double time) { time_ = time; }
    /// The simulation time of the frame, seconds.
    double frameTime() const { return time_; }

    void apply(Node& node) override;
    void apply(Group& group) override;
    void apply(Transform& transform) override;
    void apply(LOD& lod) override;
    void apply(Geometry& geometry) override;
    /// Occluders draw nothing: nothing to do.
    void apply(Occluder&) override {}

    /// Work done and results so far.
    const CullStatistics& statistics() const { return stats_; }

    // For Node::traverseCull of node types defined in other libraries.

    /// The culling frustum.
    const Frustum& frustum() const { return frustum_; }
    /// The eye position.
    const Vec3& eye() const { return eye_; }
    /// Whether the node last rejected (the one Node::culledOut is called for) was hidden by
    /// occluders rather than outside the frustum.
    bool rejectedByOcclusion() const { return rejectedByOcclusion_; }
    /// Planes still to be tested for the node being visited (its ancestors were inside the others).
    PlaneMask planeMask() const { return mask_; }
    /// Square of the LOD scale (distances are compared squared).
    double lodScaleSquared() const { return lodScale2_; }
    /// Where operations are accounted, or null.
    OpCounter* counter() const { return counter_; }
    /// World matrix of the frame the node being visited lives in.
    const Mat4& worldMatrix() const { return *world_; }
    /// Tests `sphere` against the planes in `mask`, clearing those it is inside, and accounts the
    /// test (NO_04b) unless `mask` is already empty.
    Containment testSphere(const BoundingSphere& sphere, PlaneMask& mask);
    /// Appends an item to the draw list and to the statistics, placed by `world`, with a copy of its
    /// skin palette kept by the list.
    void addDrawItem(const DrawItem& item, std::uint64_t primitives, const Mat4& world,
                     std::span<const glm::mat4> palette = {});
    /// Opens `count` segments at the end of the draw list for writers that fill them apart (the
    /// chunks of a parallel loop, see DrawList::openSegments); returns the index of the first.
    std::size_t openDrawSegments(std::size_t count) { return drawList_.openSegments(count); }
    /// Segment `i` of the draw list, opened by openDrawSegments().
    DrawSegment& drawSegment(std::size_t i) { return drawList_.segment(i); }
    /// Work counters, for nodes that cull parts themselves.
    CullStatistics& statistics() { return stats_; }

protected:
    /// Tests `node`'s world bound against the planes still in the mask, then against the occlusion
    /// buffer; false if it is outside or hidden. Clears mask bits of planes the bound is fully inside.
    bool enter(const Node& node);

    Frustum frustum_;                             ///< the camera's, or setCullingFrustum's
    Vec3 eye_;                                    ///< the camera's eye, for LOD distances
    DrawList& drawList_;                          ///< where visible items are appended
    OpCounter* counter_;                          ///< where operations are accounted, or null
    double lodScale2_;                            ///< square of the LOD scale
    PlaneMask mask_;                              ///< planes left to test for the visited node
    const Mat4* world_;                           ///< world matrix of the visited node's frame
    std::uint32_t lodLevel_ = 0;                  ///< LOD child index recorded in draw items
    double time_ = 0.0;                           ///< simulation time of the frame, seconds
    const OcclusionBuffer* occlusion_ = nullptr;  ///< occlusion buffer in use, or null
    bool rejectedByOcclusion_ = false;            ///< last node rejected was hidden, not outside
    CullStatistics stats_;                        ///< work done and results so far
};

}  // namespace throng
