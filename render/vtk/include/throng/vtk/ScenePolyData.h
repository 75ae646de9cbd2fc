#pragma once
// The static geometry of a Throng scene (a town's tiles) as VTK triangles, in world coordinates, for
// ParaView or a VTK scene. Actors are left out: they are the crowd's, recorded apart.

#include <cstdint>

#include <vtkSmartPointer.h>

class vtkPolyData;

namespace throng {
class Node;
}

namespace throng::vtk {

/// What scenePolyData found.
struct ScenePolyDataStatistics {
    std::uint64_t meshes = 0;      ///< Geometry leaves whose triangles were taken
    std::uint64_t triangles = 0;   ///< triangles written
    std::uint64_t skipped = 0;     ///< Geometry leaves without CPU triangles (not a MeshDrawable): left out
};

/// The triangles of every Geometry leaf under `root` showing a MeshDrawable, placed by the Transforms
/// above it (double-precision points: towns may lie far from the origin); LOD nodes contribute their
/// highest-detail child only; Actor, ActorGroup and Occluder nodes contribute nothing. Cell data
/// "mesh" numbers the leaf each triangle came from. Fills `stats` when given.
vtkSmartPointer<vtkPolyData> scenePolyData(Node& root, ScenePolyDataStatistics* stats = nullptr);

}  // namespace throng::vtk
