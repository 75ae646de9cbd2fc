#pragma once
// VTK's camera as Throng's: the same view and projection (OpenGL clip space), so Throng culls for
// exactly what VTK shows.

#include "throng/scenegraph/Camera.h"

class vtkCamera;

namespace throng::vtk {

/// The Throng camera of `camera` seen through a viewport of width / height `aspect` (a renderer's
/// GetTiledAspectRatio()): VTK's view matrix and its projection to -1 <= z <= 1, perspective or
/// parallel. Throws std::invalid_argument if the aspect is not positive and finite or the matrices
/// are degenerate.
Camera cameraFromVtk(vtkCamera& camera, double aspect);

}  // namespace throng::vtk
