#pragma once
// A render window's picture as a PNG file: what charts and applications write after a render.

#include <string>

class vtkRenderWindow;

namespace throng::vtk {

/// Writes what `window` last rendered (its back buffer) to `path` as a PNG. Throws
/// std::runtime_error naming the path if the file could not be written.
void writeWindowPng(vtkRenderWindow& window, const std::string& path);

}  // namespace throng::vtk
