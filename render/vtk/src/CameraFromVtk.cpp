#include "throng/vtk/CameraFromVtk.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <vtkCamera.h>
#include <vtkMatrix4x4.h>

namespace throng::vtk {
namespace {

// vtkMatrix4x4 is row-major (element [row][column]); glm is column-major (m[column][row]).
Mat4 toMat4(vtkMatrix4x4& m) {
    Mat4 out;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[c][r] = m.GetElement(r, c);
    return out;
}

}  // namespace

Camera cameraFromVtk(vtkCamera& camera, double aspect) {
    if (!(aspect > 0.0) || !std::isfinite(aspect))
        throw std::invalid_argument("cameraFromVtk: the aspect ratio must be positive and finite, not " + std::to_string(aspect));
    Camera out;
    out.setViewMatrix(toMat4(*camera.GetViewTransformMatrix()));
    out.setProjectionMatrix(toMat4(*camera.GetProjectionTransformMatrix(aspect, -1.0, 1.0)));
    return out;
}

}  // namespace throng::vtk
