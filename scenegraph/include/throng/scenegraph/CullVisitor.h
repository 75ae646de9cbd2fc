#pragma once
// The CULL traversal of traditional processing: tests world bounds against the frustum with plane
// masks, lets every LOD node compute its own eye distance, and fills the draw list.

#include <cstdint>

#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/NodeVisitor.h"

namespace throng {

class Camera;
class OpCounter;

/// Work done and results of one CULL traversal.
struct CullStatistics {
    std::uint64_t nodesVisited = 0;    ///< nodes reached
    std::uint64_t spheresTested = 0;   ///< sphere-frustum tests (NO_04b)
    std::uint64_t nodesRejected = 0;   ///< nodes found outside (their subtrees skipped)
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

    void apply(Node& node) override;
    void apply(Group& group) override;
    void apply(Transform& transform) override;
    void apply(LOD& lod) override;
    void apply(Geometry& geometry) override;

    /// Work done and results so far.
    const CullStatistics& statistics() const { return stats_; }

protected:
    /// Tests `node`'s world bound against the planes still in the mask; false if it is outside.
    /// Clears mask bits of planes the bound is fully inside.
    bool enter(const Node& node);

    Frustum frustum_;
    Vec3 eye_;
    DrawList& drawList_;
    OpCounter* counter_;
    double lodScale2_;
    PlaneMask mask_;
    const Mat4* world_;
    std::uint32_t lodLevel_ = 0;
    CullStatistics stats_;
};

}  // namespace throng
