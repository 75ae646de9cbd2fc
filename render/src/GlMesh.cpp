#include "GlMesh.h"

#include <cstring>
#include <vector>

#include "Shaders.h"
#include "SkinWeights.h"
#include "throng/render/CpuSkinning.h"

namespace throng::detail {
namespace {

const void* offset(std::size_t bytes) { return reinterpret_cast<const void*>(bytes); }

// The index buffer's contents (see GlMesh::constantIndexCount): the original indices, then, if some
// triangles are constant, every triangle again with the constant ones first. Equality is exact, so
// the colour the vertex shader computes is the one the fragment shader would have.
std::vector<std::uint32_t> withConstantFaces(const MeshData& mesh, GlMesh& g) {
    std::vector<std::uint32_t> out = mesh.indices;
    // Skinning moves normals apart; body regions are recoloured per pixel.
    if (mesh.influenceCount() > 0 || mesh.normals.empty() || !mesh.regions.empty()) return out;
    const bool textured = mesh.baseColorTexture && !mesh.texcoords.empty();
    std::vector<std::uint32_t> constant, flatLit, other;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const auto& n = mesh.normals;
        const bool oneNormal = n[a] == n[b] && n[a] == n[c];
        const bool oneTexel = !textured || (mesh.texcoords[a] == mesh.texcoords[b] && mesh.texcoords[a] == mesh.texcoords[c]);
        auto& to = !oneNormal ? other : oneTexel ? constant : flatLit;
        to.insert(to.end(), {a, b, c});
    }
    if (constant.empty() && flatLit.empty()) return out;
    g.constantIndexCount = static_cast<GLsizei>(constant.size());
    g.flatLitIndexCount = static_cast<GLsizei>(flatLit.size());
    out.insert(out.end(), constant.begin(), constant.end());
    out.insert(out.end(), flatLit.begin(), flatLit.end());
    out.insert(out.end(), other.begin(), other.end());
    return out;
}

}  // namespace

GlMesh uploadMesh(const GladGLContext& gl, const MeshData& mesh) {
    GlMesh g;
    const std::size_t n = mesh.vertexCount();
    g.vertexCount = static_cast<std::uint32_t>(n);
    g.triangleCount = static_cast<std::uint32_t>(mesh.triangleCount());
    g.indexCount = static_cast<GLsizei>(g.triangleCount * 3);
    g.influences = mesh.influenceCount();
    g.requiredPalette = requiredPaletteSize(mesh);  // also rejects non-finite weights
    g.hasNormals = !mesh.normals.empty();
    g.hasTexcoords = !mesh.texcoords.empty();
    const bool eight = g.influences == 8;

    g.hasRegions = !mesh.regions.empty();
    // Block layout: positions, normals, texcoords, joints0, weights0, joints1, weights1, regions.
    const std::size_t posBytes = n * sizeof(glm::vec3);
    const std::size_t nrmBytes = g.hasNormals ? n * sizeof(glm::vec3) : 0;
    const std::size_t uvBytes = g.hasTexcoords ? n * sizeof(glm::vec2) : 0;
    const std::size_t jBytes = g.influences > 0 ? n * sizeof(glm::u16vec4) : 0;
    const std::size_t wBytes = g.influences > 0 ? n * sizeof(glm::vec4) : 0;
    const std::size_t j1Bytes = eight ? jBytes : 0, w1Bytes = eight ? wBytes : 0;
    const std::size_t oNrm = posBytes, oUv = oNrm + nrmBytes, oJ0 = oUv + uvBytes, oW0 = oJ0 + jBytes,
                      oJ1 = oW0 + wBytes, oW1 = oJ1 + j1Bytes, oRegion = oW1 + w1Bytes,
                      total = oRegion + (g.hasRegions ? n : 0);

    g.texcoordOffset = oUv;
    g.regionOffset = oRegion;
    std::vector<unsigned char> data(total);
    std::memcpy(data.data(), mesh.positions.data(), posBytes);
    if (nrmBytes) std::memcpy(data.data() + oNrm, mesh.normals.data(), nrmBytes);
    if (uvBytes) std::memcpy(data.data() + oUv, mesh.texcoords.data(), uvBytes);
    if (g.hasRegions) std::memcpy(data.data() + oRegion, mesh.regions.data(), n);
    if (g.influences > 0) {
        auto* j0 = reinterpret_cast<glm::u16vec4*>(data.data() + oJ0);
        auto* w0 = reinterpret_cast<glm::vec4*>(data.data() + oW0);
        auto* j1 = eight ? reinterpret_cast<glm::u16vec4*>(data.data() + oJ1) : nullptr;
        auto* w1 = eight ? reinterpret_cast<glm::vec4*>(data.data() + oW1) : nullptr;
        for (std::size_t v = 0; v < n; ++v) {
            glm::vec4 a, b;
            normalisedWeights(mesh, v, eight, a, b);
            glm::u16vec4 ja = mesh.joints0[v];
            for (int k = 0; k < 4; ++k)
                if (a[k] == 0.0f) ja[k] = 0;
            std::memcpy(&j0[v], &ja, sizeof ja);
            std::memcpy(&w0[v], &a, sizeof a);
            if (eight) {
                glm::u16vec4 jb = mesh.joints1[v];
                for (int k = 0; k < 4; ++k)
                    if (b[k] == 0.0f) jb[k] = 0;
                std::memcpy(&j1[v], &jb, sizeof jb);
                std::memcpy(&w1[v], &b, sizeof b);
            }
        }
    }

    gl.GenVertexArrays(1, &g.vao);
    gl.GenBuffers(1, &g.vbo);
    gl.GenBuffers(1, &g.ibo);
    gl.BindVertexArray(g.vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, g.vbo);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(total), data.data(), GL_STATIC_DRAW);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ibo);  // recorded in the vertex array
    const std::vector<std::uint32_t> indices = withConstantFaces(mesh, g);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                  indices.empty() ? nullptr : indices.data(), GL_STATIC_DRAW);
    gl.EnableVertexAttribArray(kPosition);
    gl.VertexAttribPointer(kPosition, 3, GL_FLOAT, GL_FALSE, 0, offset(0));
    if (g.hasNormals) {
        gl.EnableVertexAttribArray(kNormal);
        gl.VertexAttribPointer(kNormal, 3, GL_FLOAT, GL_FALSE, 0, offset(oNrm));
    }
    if (g.hasTexcoords) {
        gl.EnableVertexAttribArray(kTexcoord);
        gl.VertexAttribPointer(kTexcoord, 2, GL_FLOAT, GL_FALSE, 0, offset(oUv));
    }
    if (g.hasRegions) enableRegions(gl, g);
    if (g.influences > 0) {
        gl.EnableVertexAttribArray(kJoints0);
        gl.VertexAttribIPointer(kJoints0, 4, GL_UNSIGNED_SHORT, 0, offset(oJ0));
        gl.EnableVertexAttribArray(kWeights0);
        gl.VertexAttribPointer(kWeights0, 4, GL_FLOAT, GL_FALSE, 0, offset(oW0));
    }
    if (eight) {
        gl.EnableVertexAttribArray(kJoints1);
        gl.VertexAttribIPointer(kJoints1, 4, GL_UNSIGNED_SHORT, 0, offset(oJ1));
        gl.EnableVertexAttribArray(kWeights1);
        gl.VertexAttribPointer(kWeights1, 4, GL_FLOAT, GL_FALSE, 0, offset(oW1));
    }
    gl.BindVertexArray(0);
    if (!mesh.morphTargets.empty()) {
        // Target by target, vertex by vertex: the position offset, then the normal offset (zero
        // where the target has none).
        g.morphTargets = static_cast<std::uint32_t>(mesh.morphTargets.size());
        std::vector<glm::vec4> texels(mesh.morphTargets.size() * n * kMorphTexelsPerVertex, glm::vec4(0.0f));
        for (std::size_t k = 0; k < mesh.morphTargets.size(); ++k) {
            const MorphTarget& t = mesh.morphTargets[k];
            for (std::size_t v = 0; v < n; ++v) {
                glm::vec4* at = texels.data() + (k * n + v) * kMorphTexelsPerVertex;
                at[0] = glm::vec4(t.positions[v], 0.0f);
                if (!t.normals.empty()) at[1] = glm::vec4(t.normals[v], 0.0f);
            }
        }
        g.morphBytes = texels.size() * sizeof(glm::vec4);
        gl.GenBuffers(1, &g.morphBuffer);
        gl.BindBuffer(GL_TEXTURE_BUFFER, g.morphBuffer);
        gl.BufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(g.morphBytes), texels.data(), GL_STATIC_DRAW);
        gl.GenTextures(1, &g.morphTexture);
        gl.ActiveTexture(GL_TEXTURE0 + kMorphOffsetUnit);
        gl.BindTexture(GL_TEXTURE_BUFFER, g.morphTexture);
        gl.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, g.morphBuffer);
        gl.BindBuffer(GL_TEXTURE_BUFFER, 0);
        gl.ActiveTexture(GL_TEXTURE0);
    }
    return g;
}

void enableRegions(const GladGLContext& gl, const GlMesh& mesh) {
    gl.EnableVertexAttribArray(kRegion);  // small integers as floats: the shader compares them
    gl.VertexAttribPointer(kRegion, 1, GL_UNSIGNED_BYTE, GL_FALSE, 0, offset(mesh.regionOffset));
}

void destroyMesh(const GladGLContext& gl, GlMesh& mesh) {
    if (mesh.vao) gl.DeleteVertexArrays(1, &mesh.vao);
    if (mesh.vbo) gl.DeleteBuffers(1, &mesh.vbo);
    if (mesh.ibo) gl.DeleteBuffers(1, &mesh.ibo);
    if (mesh.morphBuffer) gl.DeleteBuffers(1, &mesh.morphBuffer);
    if (mesh.morphTexture) gl.DeleteTextures(1, &mesh.morphTexture);
    mesh = GlMesh{};
}

}  // namespace throng::detail
