#pragma once
// Internal: the rigid template of a glTF file's unskinned primitives (a town tile, a prop): one
// DOF-less Skeleton node per primitive, its mesh already in world space.

#include <optional>
#include <set>
#include <string>

#include "GltfContent.h"
#include "GltfDocument.h"
#include "throng/gltf/GltfLoadOptions.h"
#include "throng/gltf/LoadedCharacter.h"

namespace throng::gltf {

/// The template of the unskinned primitives of `content` not in `claimed` (drawn as a skin's
/// joint geometry), named `name` ("name/static" when the file has skins); nothing when there is
/// none. Throws GltfError.
std::optional<LoadedCharacter> buildStaticTemplate(GltfDocument& doc, const GltfContent& content, const std::set<int>& claimed,
                                                   const GltfLoadOptions& options, const std::string& name);

}  // namespace throng::gltf
