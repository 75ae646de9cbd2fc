#pragma once
// Reads a scene file into a SceneDescription, checking every value: a wrong type, a missing field,
// an unknown key or behaviour, a negative count or a missing asset gives a SceneError naming the
// JSON path and the reason. Nothing is constructed here.

#include <string>

#include "throng/sim/SceneDescription.h"

namespace throng::sim {

/// Parses the scene file at `path` (relative paths inside it resolve against its folder).
SceneDescription parseSceneFile(const std::string& path);
/// Parses scene JSON text; relative paths resolve against `baseDirectory`; `file` names it in errors.
SceneDescription parseScene(const std::string& text, const std::string& baseDirectory, const std::string& file = "<text>");

}  // namespace throng::sim
