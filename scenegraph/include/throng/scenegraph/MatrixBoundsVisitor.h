#pragma once
// Between APP and CULL in traditional processing: builds local matrices from DOFs, composes world
// matrices on the CPU top-down and recomputes world bounding spheres bottom-up. Subtrees whose
// matrices and contents did not change keep their cached results (temporal coherence) unless a
// full recompute is requested.

#include <cstdint>

#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/Node.h"
#include "throng/scenegraph/NodeVisitor.h"

namespace throng {

class OpCounter;

/// Work done by one pass.
struct MatrixBoundsStatistics {
    std::uint64_t localMatricesBuilt = 0;   ///< Transforms whose DOFs were turned into a matrix
    std::uint64_t worldMatricesComposed = 0;///< parent * local products on the CPU
    std::uint64_t spheresRecomputed = 0;    ///< nodes whose world bound was recomputed
};

/// Updates world matrices and world bounds of a tree.
class MatrixBoundsVisitor : public NodeVisitor {
public:
    /// A pass accounting into `counter` (may be null); with `fullRecompute`, nothing is reused.
    explicit MatrixBoundsVisitor(OpCounter* counter = nullptr, bool fullRecompute = false);

    void apply(Node& node) override;
    void apply(Group& group) override;
    void apply(Transform& transform) override;
    void apply(LOD& lod) override;
    void apply(Geometry& geometry) override;

    /// Work done so far.
    const MatrixBoundsStatistics& statistics() const { return stats_; }

    // For Node::updateMatricesAndBound of node types defined in other libraries.

    /// World matrix of the frame the node being visited lives in.
    const Mat4& parentWorld() const { return *parentWorld_; }
    /// Whether that frame is the world itself (no Transform above), so products with it can be skipped.
    bool parentIsIdentity() const;
    /// Whether that frame changed since the node was last visited (or everything is recomputed).
    bool frameChanged(const Node& node) const { return parentChanged_ || fullRecompute_ || node.worldStale(); }
    /// Where operations are accounted, or null.
    OpCounter* counter() const { return counter_; }
    /// Whether nothing may be reused from the previous frame.
    bool fullRecompute() const { return fullRecompute_; }
    /// Work counters, for nodes that do matrix and bound work themselves.
    MatrixBoundsStatistics& statistics() { return stats_; }

private:
    bool needsVisit(const Node& node) const { return fullRecompute_ || parentChanged_ || node.boundDirty(); }
    void mergeChildren(Group& group);

    OpCounter* counter_;
    bool fullRecompute_;
    const Mat4* parentWorld_;
    bool parentChanged_ = false;
    MatrixBoundsStatistics stats_;
};

}  // namespace throng
