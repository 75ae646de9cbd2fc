#include "throng/render/CpuSkinning.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "SkinWeights.h"

namespace throng {
namespace {

[[noreturn]] void fail(const char* where, const MeshData& mesh, const std::string& what) {
    throw std::invalid_argument(std::string(where) + ": mesh '" + mesh.name + "': " + what);
}

bool finite(const glm::vec4& w) {
    return std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z) && std::isfinite(w.w);
}

const glm::mat4 kIdentity(1.0f);

// Blends the palette matrices of vertex v. Out-of-palette joints read the identity (so memory is
// never read out of bounds) and set `bad` when their weight is not zero.
template <bool Eight>
glm::mat4 blend(const MeshData& mesh, std::size_t v, const glm::vec4& w0, const glm::vec4& w1,
                const glm::mat4* palette, std::uint32_t size, bool& bad) {
    const auto at = [&](unsigned j, float w) -> const glm::mat4& {
        const bool inside = j < size;
        bad |= !inside & (w != 0.0f);
        return inside ? palette[j] : kIdentity;
    };
    const glm::u16vec4 j0 = mesh.joints0[v];
    glm::mat4 s = at(j0.x, w0.x) * w0.x + at(j0.y, w0.y) * w0.y + at(j0.z, w0.z) * w0.z + at(j0.w, w0.w) * w0.w;
    if constexpr (Eight) {
        const glm::u16vec4 j1 = mesh.joints1[v];
        s = s + at(j1.x, w1.x) * w1.x + at(j1.y, w1.y) * w1.y + at(j1.z, w1.z) * w1.z + at(j1.w, w1.w) * w1.w;
    }
    return s;
}

template <bool Eight>
bool skinAll(const MeshData& mesh, std::span<const glm::mat4> palette, std::span<glm::vec3> positions,
             std::span<glm::vec3> normals, const glm::vec3* sourcePositions, const glm::vec3* sourceNormals) {
    const std::size_t n = mesh.vertexCount();
    const bool doNormals = !normals.empty() && !mesh.normals.empty();
    const glm::mat4* pal = palette.data();
    const auto size = static_cast<std::uint32_t>(palette.size());
    bool bad = false;
    for (std::size_t v = 0; v < n; ++v) {
        glm::vec4 w0, w1;
        detail::normalisedWeights(mesh, v, Eight, w0, w1);
        const glm::vec3 p = sourcePositions[v];
        if (w0 == glm::vec4(0.0f) && w1 == glm::vec4(0.0f)) {  // no influence: bind pose
            positions[v] = p;
            if (doNormals) {
                const glm::vec3 q = sourceNormals[v];
                const float len = glm::length(q);
                normals[v] = len > 0.0f ? q / len : q;
            }
            continue;
        }
        const glm::mat4 s = blend<Eight>(mesh, v, w0, w1, pal, size, bad);
        positions[v] = glm::vec3(s * glm::vec4(p, 1.0f));  // affine: the bottom row is ignored
        if (doNormals) {
            const glm::vec3 q = glm::mat3(s) * sourceNormals[v];
            const float len = glm::length(q);
            normals[v] = len > 0.0f ? q / len : q;
        }
    }
    return !bad;
}

}  // namespace

std::uint32_t requiredPaletteSize(const MeshData& mesh) {
    if (!mesh.skinned()) return 0;
    const bool eight = mesh.influenceCount() == 8;
    std::uint32_t required = 0;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const glm::vec4 w0 = mesh.weights0[v];
        const glm::vec4 w1 = eight ? mesh.weights1[v] : glm::vec4(0.0f);
        if (!finite(w0) || !finite(w1))
            fail("requiredPaletteSize", mesh, "skin weight of vertex " + std::to_string(v) + " is not finite");
        const glm::u16vec4 j0 = mesh.joints0[v];
        const glm::u16vec4 j1 = eight ? mesh.joints1[v] : glm::u16vec4(0);
        for (int k = 0; k < 4; ++k) {
            if (w0[k] != 0.0f) required = std::max<std::uint32_t>(required, j0[k] + 1u);
            if (w1[k] != 0.0f) required = std::max<std::uint32_t>(required, j1[k] + 1u);
        }
    }
    return required;
}

void skinMesh(const MeshData& mesh, std::span<const glm::mat4> palette, std::span<glm::vec3> positions,
              std::span<glm::vec3> normals, std::span<const glm::vec3> sourcePositions, std::span<const glm::vec3> sourceNormals) {
    const char* where = "skinMesh";
    if (!mesh.skinned()) fail(where, mesh, "is not skinned (it has no joints0/weights0)");
    const std::size_t n = mesh.vertexCount();
    if (mesh.weights0.size() != n || mesh.joints0.size() != n)
        fail(where, mesh, "has skin arrays whose sizes do not match its " + std::to_string(n) + " vertices");
    if (mesh.influenceCount() == 8 && (mesh.weights1.size() != n || mesh.joints1.size() != n))
        fail(where, mesh, "has joints1/weights1 arrays whose sizes do not match its vertices");
    if (positions.size() != n)
        fail(where, mesh, "output 'positions' holds " + std::to_string(positions.size()) + " vertices, the mesh has " +
                              std::to_string(n));
    if (!normals.empty() && normals.size() != n)
        fail(where, mesh, "output 'normals' holds " + std::to_string(normals.size()) + " vertices, the mesh has " +
                              std::to_string(n));
    if (!sourcePositions.empty() && sourcePositions.size() != n)
        fail(where, mesh, "'sourcePositions' holds " + std::to_string(sourcePositions.size()) + " vertices, the mesh has " +
                              std::to_string(n));
    const bool doNormals = !normals.empty() && !mesh.normals.empty();
    if (doNormals && !sourceNormals.empty() && sourceNormals.size() != n)
        fail(where, mesh, "'sourceNormals' holds " + std::to_string(sourceNormals.size()) + " vertices, the mesh has " +
                              std::to_string(n));
    const glm::vec3* p = sourcePositions.empty() ? mesh.positions.data() : sourcePositions.data();
    const glm::vec3* q = sourceNormals.empty() || !doNormals ? mesh.normals.data() : sourceNormals.data();
    const bool ok = mesh.influenceCount() == 8 ? skinAll<true>(mesh, palette, positions, normals, p, q)
                                               : skinAll<false>(mesh, palette, positions, normals, p, q);
    if (!ok)  // rare: find what to name (the slow scan runs only on error)
        fail(where, mesh, "a joint index needs a palette of " + std::to_string(requiredPaletteSize(mesh)) +
                              " matrices, the palette has " + std::to_string(palette.size()));
}

}  // namespace throng
