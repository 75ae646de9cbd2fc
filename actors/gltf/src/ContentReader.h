#pragma once
// Internal: the first half of the glTF loader, reading and checking. Walks the document once,
// checks every reference, matrix, accessor and key it uses (a GltfError with the JSON pointer of the
// first bad value), warns about what it skips or fixes, and hands the template builders a
// GltfContent they can trust.

#include <map>
#include <memory>
#include <set>

#include "AccessorReader.h"
#include "GltfContent.h"
#include "GltfDocument.h"
#include "throng/gltf/CharacterAsset.h"
#include "throng/gltf/GltfLoadOptions.h"
#include "throng/scenegraph/Image.h"

namespace throng::gltf {

/// Reads one document (once).
class ContentReader {
public:
    /// A reader of `doc` that records each primitive instance in `asset.primitives` and each
    /// animation in `asset.animations` (all three must outlive it).
    ContentReader(GltfDocument& doc, const GltfLoadOptions& options, CharacterAsset& asset)
        : doc_(doc), m_(doc.model), options_(options), reader_(doc, options.limits), asset_(asset) {}

    /// Reads and checks, in this order: the node tree, the default scene, the skins, the mesh
    /// primitives of the scene (textures decoded as they are needed) and the animations.
    GltfContent read();

private:
    // Parents (one each, no cycle), local matrices and their T R S split, world matrices.
    void readNodes();
    // The default scene's nodes, depth first.
    void readScene();
    // Joint lists, skeleton roots and inverse bind matrices of every skin; what glTF skinning
    // ignores about the nodes that use a skin (a warning each).
    void checkSkins();
    // Every primitive of every mesh node of the scene.
    void readPrimitives();
    // One primitive: positions, normals, material colour and texture, triangles, skin influences.
    ReadPrimitive readPrimitive(int nodeIndex, int meshIndex, int p);
    // The morph targets of primitive `prim` of mesh `meshIndex` (at `where`) into `mesh`, whose
    // positions and normals are read: offsets checked against its vertex count.
    void readMorphTargets(int meshIndex, const tinygltf::Primitive& prim, const std::string& where, MeshData& mesh);
    // The morph target names of mesh `meshIndex` (checked once: target counts of its primitives,
    // its default weights, its extras.targetNames), unique within the mesh.
    const std::vector<std::string>& targetNames(int meshIndex);
    // glTF image `imageIndex` decoded (once), or null (with a warning) when it cannot be.
    std::shared_ptr<const Image> texture(int imageIndex);
    // The channels that drive joints or nodes above them, with their keys checked.
    void readAnimations();

    GltfDocument& doc_;
    tinygltf::Model& m_;
    const GltfLoadOptions& options_;
    AccessorReader reader_;
    CharacterAsset& asset_;
    GltfContent c_;  // what read() returns, filled step by step
    std::map<int, std::shared_ptr<const Image>> images_;
    std::set<int> badImages_;
};

}  // namespace throng::gltf
