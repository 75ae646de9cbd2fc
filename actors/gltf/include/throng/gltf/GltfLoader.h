#pragma once
// The glTF 2.0 character loader: .gltf (with external or embedded buffers) and .glb files become
// actor templates (one per skin), clips and draw-ready meshes. Every value read is checked: a bad
// file throws GltfError naming the JSON pointer of the culprit, never crashes.

#include <cstdint>
#include <string>
#include <vector>

#include "throng/gltf/CharacterAsset.h"
#include "throng/gltf/GltfError.h"
#include "throng/gltf/GltfLoadOptions.h"

namespace throng {

/// Loads the glTF or GLB file at `path`. Throws GltfError.
CharacterAsset loadCharacter(const std::string& path, const GltfLoadOptions& options = {});
/// Loads a glTF or GLB document held in memory; `name` names it in messages and templates.
/// Throws GltfError.
CharacterAsset loadCharacterFromMemory(const std::vector<std::uint8_t>& bytes, const std::string& name,
                                       const GltfLoadOptions& options = {});

}  // namespace throng
