#pragma once
// Coarser versions of a mesh for geometric LOD (vaLod levels), made with meshoptimizer. Skinned
// meshes keep their influences: simplification only drops triangles and unused vertices, so the
// surviving vertices deform exactly as before.

#include <memory>

#include "throng/scenegraph/MeshData.h"

namespace throng {

/// A simplified mesh and what it lost.
struct SimplifiedMesh {
    std::shared_ptr<MeshData> mesh;  ///< the coarser mesh, only the vertices it uses
    double error = 0.0;              ///< largest surface deviation meshoptimizer measured, in the mesh's units
    bool sloppy = false;             ///< the topology-keeping simplifier stalled above the target; the sloppy one made it
};

/// Simplifies `mesh` to about `triangleShare` (0 < share <= 1) of its triangles. Seams (UV or
/// normal splits) are kept while possible; if the careful simplifier cannot get within 1.5x of the
/// target, the sloppy one (which welds across seams) is used. Throws std::invalid_argument naming
/// the mesh when the share is not in (0, 1] or the mesh is invalid.
SimplifiedMesh simplifyMesh(const MeshData& mesh, double triangleShare);

}  // namespace throng
