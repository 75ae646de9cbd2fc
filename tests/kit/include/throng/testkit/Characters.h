#pragma once
// The glTF characters of the shared assets, each loaded once per test program: loading CesiumMan
// or the robot takes longer than most tests that draw them.

#include <string>

#include "throng/gltf/GltfLoader.h"

namespace throng::testkit {

/// The character `file` of the shared assets' characters/ folder (e.g. "CesiumMan.glb"), loaded on
/// the first call and kept for the program's life. Throws as loadCharacter does.
const CharacterAsset& sharedCharacter(const std::string& file);

}  // namespace throng::testkit
