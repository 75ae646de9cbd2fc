#pragma once
// A triangle mesh on the CPU with one material, optionally skinned (up to 8 joint influences per
// vertex, in two sets of four as glTF stores them). Shared by every clone that shows it; renderers
// upload it once.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <glm/gtc/type_precision.hpp>

#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/Image.h"
#include "throng/scenegraph/MorphTarget.h"

namespace throng {

/// Indexed triangles with per-vertex attributes, in the mesh's own frame (float: meshes are small).
struct MeshData {
    std::string name;                          ///< for messages and statistics
    std::vector<glm::vec3> positions;          ///< one per vertex
    std::vector<glm::vec3> normals;            ///< one per vertex, or empty (flat shading)
    std::vector<glm::vec2> texcoords;          ///< one per vertex, or empty
    std::vector<std::uint32_t> indices;        ///< three per triangle
    std::vector<glm::u16vec4> joints0;         ///< skin: first four joint indices per vertex, or empty
    std::vector<glm::vec4> weights0;           ///< skin: their weights
    std::vector<glm::u16vec4> joints1;         ///< skin: influences 5-8 per vertex, or empty
    std::vector<glm::vec4> weights1;           ///< skin: their weights
    /// Body region per vertex (BodyRegion values; BodyLook recolours them), or empty: none.
    std::vector<std::uint8_t> regions;
    /// Morph targets (blend shapes) added before skinning, weighted per actor; names unique.
    std::vector<MorphTarget> morphTargets;
    glm::vec4 baseColor{1.0f};                 ///< multiplies the texture (linear RGBA)
    std::shared_ptr<const Image> baseColorTexture;  ///< or null

    /// Number of vertices.
    std::size_t vertexCount() const { return positions.size(); }
    /// Number of triangles.
    std::size_t triangleCount() const { return indices.size() / 3; }
    /// Whether the mesh carries skin influences.
    bool skinned() const { return !joints0.empty(); }
    /// Number of influences per vertex (0, 4 or 8).
    int influenceCount() const { return joints0.empty() ? 0 : joints1.empty() ? 4 : 8; }
    /// The skin joint with the largest weight on vertex `v` (the first of equals); the mesh must be
    /// skinned and `v` in range.
    std::uint32_t strongestJoint(std::size_t v) const;

    /// Index of the morph target named `name`, or -1.
    int findMorphTarget(const std::string& targetName) const;

    /// Throws std::invalid_argument naming the mesh and the problem if attribute counts disagree,
    /// a region is not a BodyRegion, an index is out of range, the index count is not a multiple of
    /// 3, a value is not finite, or a morph target is unnamed, named twice or sized unlike the mesh.
    void validate() const;
    /// Smallest-ish sphere holding every vertex (in the mesh frame), grown by the largest offset of
    /// every morph target so that it holds every shape weights up to kMaxMorphWeight make. Throws
    /// if there is no vertex.
    BoundingSphere computeBound() const;
};

}  // namespace throng
