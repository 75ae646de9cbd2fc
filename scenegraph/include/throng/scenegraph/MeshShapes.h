#pragma once
// Procedural meshes (boxes, capsules, spheres) with a chosen tessellation: rigid segments of
// procedural actors at several levels of detail, props, and test scenes.

#include <memory>
#include <string>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "throng/scenegraph/MeshData.h"

namespace throng {

/// An axis-aligned box centred on `center` with half sizes `halfExtents`: 24 vertices with face
/// normals and per-face texture coordinates (the image's top row at the top of each side face),
/// counter-clockwise from outside (12 triangles).
std::shared_ptr<MeshData> makeBox(std::string name, const glm::vec3& center, const glm::vec3& halfExtents,
                                  const glm::vec4& color = glm::vec4(1.0f));
/// A capsule along +Y from `base` (a cylinder of `radius` and `length` with hemispherical caps),
/// with `segments` around (>= 3) and `rings` per cap (>= 1).
std::shared_ptr<MeshData> makeCapsule(std::string name, const glm::vec3& base, float radius, float length,
                                      int segments, int rings, const glm::vec4& color = glm::vec4(1.0f));
/// A UV sphere with `segments` around (>= 3) and `rings` from pole to pole (>= 2).
std::shared_ptr<MeshData> makeSphere(std::string name, const glm::vec3& center, float radius, int segments, int rings,
                                     const glm::vec4& color = glm::vec4(1.0f));
/// `a` and `b` in one mesh (same material: a's colour).
std::shared_ptr<MeshData> mergeMeshes(std::string name, const MeshData& a, const MeshData& b);

}  // namespace throng
