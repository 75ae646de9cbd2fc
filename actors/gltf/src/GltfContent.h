#pragma once
// Internal: what ContentReader read and checked from a glTF document, in the loader's terms, before
// any template is built: the node tree with its matrices, the default scene, the skins, the mesh
// primitives and the animation channels. The template builders only read it.

#include <memory>
#include <set>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include "TransformMath.h"
#include "throng/actors/AnimationClip.h"
#include "throng/scenegraph/MeshData.h"

namespace throng::gltf {

/// One primitive read from the file, before it goes to a template (parallel to
/// CharacterAsset::primitives).
struct ReadPrimitive {
    int mesh = -1, primitive = -1, node = -1, skin = -1, material = -1;  ///< where it came from
    std::shared_ptr<MeshData> local;         ///< mesh space (skinned: joint indices of the skin)
    std::shared_ptr<const MeshData> world;   ///< unskinned: world space
    int texture = -1;                        ///< glTF image drawn, or -1
};

/// One animation channel that drives a joint or a node above one (the others are not read).
struct ReadChannel {
    int node = -1;   ///< glTF node driven
    int path = 0;    ///< 0 translation, 1 rotation, 2 scale, 3 morph weights
    int targets = 0; ///< morph weights: the morph targets of the node's mesh (values per key)
    int index = 0;   ///< channel index in the animation
    Interpolation interpolation = Interpolation::Linear;  ///< as the sampler says
    std::shared_ptr<const std::vector<float>> times;      ///< key times, shared by channels of one sampler
    std::shared_ptr<const std::vector<float>> values;     ///< key values, as in the file
};

/// The checked content of a document.
struct GltfContent {
    std::vector<int> parent;          ///< per node: parent node, or -1
    std::vector<dmat4> local;         ///< per node: local matrix
    std::vector<dmat4> world;         ///< per node: world matrix, GltfLoadOptions::scale included
    std::vector<Trs> trs;             ///< per node: the local transform split
    std::vector<char> inScene;        ///< per node: part of the default scene
    std::vector<int> order;           ///< nodes of the default scene, depth first
    std::vector<std::vector<int>> skinJoints;          ///< per skin: its joints' glTF nodes
    std::vector<std::vector<glm::mat4>> inverseBinds;  ///< per skin: one per joint
    std::vector<ReadPrimitive> primitives;             ///< every primitive instance of the scene
    std::vector<std::vector<ReadChannel>> channels;    ///< per animation: channels read
    std::vector<std::vector<std::string>> targetNames; ///< per mesh: its morph targets' names (unique), when read
    std::set<int> animatedNodes;      ///< nodes some read channel drives
};

/// The name of glTF node `n`, or "node<n>" when it has none.
inline std::string nodeName(const tinygltf::Model& model, int n) {
    const std::string& nm = model.nodes[static_cast<std::size_t>(n)].name;
    return nm.empty() ? "node" + std::to_string(n) : nm;
}

}  // namespace throng::gltf
