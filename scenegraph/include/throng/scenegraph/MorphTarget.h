#pragma once
// A morph target (blend shape, glTF "targets"): per-vertex offsets a mesh adds, scaled by a weight,
// before it is skinned or placed. Faces are made of them: a smile, a frown, closed eyelids.

#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace throng {

struct MeshData;

/// One target of a mesh: what weight 1 adds to each vertex.
struct MorphTarget {
    std::string name;                  ///< e.g. "Angry"; a template's meshes share a weight per name
    std::vector<glm::vec3> positions;  ///< position offset per vertex
    std::vector<glm::vec3> normals;    ///< normal offset per vertex, or empty (normals unchanged)
    float defaultWeight = 0.0f;        ///< weight at rest (glTF mesh.weights)
};

/// Weights a mesh applies are clamped to this range: the one its bounds are made for
/// (MeshData::computeBound grows by every target's largest offset).
inline constexpr float kMaxMorphWeight = 1.0f;

/// Writes `mesh`'s positions plus the weighted target offsets into `positions`, and its normals
/// plus the weighted normal offsets into `normals` (left unnormalised, as skinning normalises;
/// may be empty to skip them, and is left untouched for a mesh without normals). `weights` holds
/// one weight per target of the mesh, each clamped to [-kMaxMorphWeight, kMaxMorphWeight]; zero
/// weights cost nothing. The CPU reference of the renderer's morphing; throws std::invalid_argument
/// naming the mesh if a span has the wrong size or a weight is not finite.
void applyMorphTargets(const MeshData& mesh, std::span<const float> weights, std::span<glm::vec3> positions,
                       std::span<glm::vec3> normals);

}  // namespace throng
