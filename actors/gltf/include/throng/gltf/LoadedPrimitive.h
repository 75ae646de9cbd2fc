#pragma once
// One glTF mesh primitive as the loader read it: where it came from and its mesh data.

#include <memory>

#include "throng/scenegraph/MeshData.h"

namespace throng {

/// A mesh primitive of a glTF file, once per node that instantiates it.
struct LoadedPrimitive {
    int mesh = -1;       ///< glTF mesh index
    int primitive = -1;  ///< primitive index within the mesh
    int node = -1;       ///< glTF node instantiating it
    int skin = -1;       ///< glTF skin deforming it, or -1
    int material = -1;   ///< glTF material, or -1
    /// The triangles. Unskinned: positions and normals in world space (the node's world matrix in
    /// the default scene), ready to draw as they are. Skinned: mesh space, joint indices of the skin.
    std::shared_ptr<const MeshData> data;
};

}  // namespace throng
