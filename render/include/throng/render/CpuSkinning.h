#pragma once
// Linear-blend skinning on the CPU: the reference for the GPU path, and the producer of skinned
// key-poses for a key-pose cache. Computes exactly what the renderer's vertex shader computes.

#include <cstdint>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "throng/scenegraph/MeshData.h"

namespace throng {

/// The palette size `mesh` needs: one more than the largest joint index carrying a non-zero
/// weight (0 for an unskinned mesh). Scans every influence: call it once per mesh, not per frame.
std::uint32_t requiredPaletteSize(const MeshData& mesh);

/// Skins `mesh` with `palette` (joint-to-model times inverse bind, one matrix per joint, treated as
/// affine) into `positions` and `normals` (one per vertex; `normals` may be empty to skip them, and
/// is left untouched for a mesh without normals). Each vertex's weights are divided by their sum
/// (4 or 8 influences); a vertex whose weights sum to zero keeps its bind position. Normals are
/// transformed by the blended matrix's upper 3x3 and normalised.
/// `sourcePositions` and `sourceNormals`, when not empty, are skinned instead of the mesh's own
/// (its morphed shape, from applyMorphTargets: targets go before skinning); they may be the
/// output spans themselves.
/// Throws std::invalid_argument naming the mesh if a span has the wrong size, the mesh is
/// not skinned, or a joint with a non-zero weight is outside `palette` (outputs are then partial).
void skinMesh(const MeshData& mesh, std::span<const glm::mat4> palette, std::span<glm::vec3> positions,
              std::span<glm::vec3> normals, std::span<const glm::vec3> sourcePositions = {},
              std::span<const glm::vec3> sourceNormals = {});

}  // namespace throng
