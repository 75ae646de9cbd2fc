#pragma once
// Private: a MeshData's GPU copy (one vertex buffer holding each attribute in its own block, an
// index buffer, a vertex array with the static attributes) shared by the renderer and the
// transform-feedback skinner.

#include <cstdint>

#include <glad/gl.h>

#include "throng/scenegraph/MeshData.h"

namespace throng::detail {

/// GPU buffers of one mesh and what the draw code needs to know about it.
struct GlMesh {
    GLuint vbo = 0, ibo = 0, vao = 0;
    GLsizei indexCount = 0;
    /// Constant faces (rigid meshes with normals): triangles whose three vertices share one normal
    /// and one texture coordinate (or the mesh has no texture) have one colour over their whole
    /// surface, so it can be shaded once per vertex. `ibo` holds the original indices, then (when
    /// there are such triangles) the same triangles again, constant ones first in their original
    /// order, then flat-lit ones (one normal, texture coordinates that vary: the light cannot vary
    /// over them), then the others; this many are constant, and `flatLitIndexCount` flat-lit.
    GLsizei constantIndexCount = 0;
    GLsizei flatLitIndexCount = 0;
    std::uint32_t vertexCount = 0;
    std::uint32_t triangleCount = 0;
    int influences = 0;                ///< 0, 4 or 8
    std::uint32_t requiredPalette = 0; ///< palette size the joint indices need
    bool hasNormals = false;
    bool hasTexcoords = false;
    std::size_t texcoordOffset = 0;    ///< byte offset of the texture coordinates in `vbo`
    bool hasRegions = false;           ///< the mesh has body regions (one byte per vertex)
    std::size_t regionOffset = 0;      ///< byte offset of the body regions in `vbo`
    std::uint32_t morphTargets = 0;    ///< morph targets of the mesh
    GLuint morphBuffer = 0, morphTexture = 0;  ///< their offsets (see kMorphTexelsPerVertex), a texture buffer
    std::size_t morphBytes = 0;        ///< of `morphBuffer`
};

/// Uploads `mesh` (weights normalised as skinMesh() does; joints of zero-weight influences set to 0
/// so that no fetch can leave the palette; morph target offsets into a texture buffer) and records
/// vertex array state for the attributes it has. Throws std::invalid_argument naming the mesh if a skin weight is not finite.
GlMesh uploadMesh(const GladGLContext& gl, const MeshData& mesh);

/// Points attribute kRegion of the bound vertex array at `mesh`'s body regions (array buffer
/// `mesh.vbo` bound); a vertex array without it reads region 0, none.
void enableRegions(const GladGLContext& gl, const GlMesh& mesh);

/// Deletes the buffers and the vertex array (context current).
void destroyMesh(const GladGLContext& gl, GlMesh& mesh);

}  // namespace throng::detail
