#pragma once
// Internal: the primitives of one skin become one skinned mesh (one draw per actor), with one
// texture: the image most of their triangles use, or a palette of their base colours when they
// have no texture but several colours.

#include <memory>
#include <string>
#include <vector>

#include "GltfContent.h"
#include "GltfDocument.h"
#include "throng/scenegraph/MeshData.h"

namespace throng::gltf {

/// Merges `primitives[i]` for each i of `which` (all of one skin) into one mesh named `name`.
/// Several textures keep the one with most triangles, with a warning at `where`.
std::shared_ptr<MeshData> mergeSkinnedPrimitives(GltfDocument& doc, const std::vector<ReadPrimitive>& primitives,
                                                 const std::vector<int>& which, const std::string& name,
                                                 const std::string& where);

}  // namespace throng::gltf
