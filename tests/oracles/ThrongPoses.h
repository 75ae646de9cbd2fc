#pragma once
// Throng's side of the oracles: where the shared characters are, the vertex positions Throng draws
// for a draw list (CPU skinning of each item's palette, placed by its world matrix), and the
// perturbation of one joint used by the negative controls.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "throng/gltf/CharacterAsset.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/MeshData.h"

namespace throng::test {

/// Path of characters/<file> in the shared assets.
std::string characterPath(const std::string& file);

/// `file` loaded with `scale`, once per (file, scale) for the whole test program.
const CharacterAsset& loadedCharacter(const std::string& file, double scale);

/// World positions of every mesh vertex `list` draws, item by item in order: skinned items are
/// skinned on the CPU (skinMesh) with their palette, or with `palette` for the first skinned item
/// when it is not empty. Throws std::invalid_argument if an item is not a MeshDrawable.
std::vector<glm::dvec3> drawnPositions(const DrawList& list, std::span<const glm::mat4> palette = {});

/// The skin joint that carries the largest weight of the most vertices of `mesh`.
std::uint32_t busiestJoint(const MeshData& mesh);

/// A palette entry (joint-to-model times inverse bind) whose joint is turned by `angle` radians
/// about `axis` (model frame) through the joint's posed origin: the vertices bound to that joint
/// swing as if the joint alone were rotated, its children staying where they were.
glm::mat4 rotatedAboutJoint(const glm::mat4& entry, const glm::mat4& inverseBind, double angle, const glm::dvec3& axis);

}  // namespace throng::test
