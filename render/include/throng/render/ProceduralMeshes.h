#pragma once
// Procedural test and debug geometry: quads, checker textures and skinned tubes with a bending pose,
// so tests and benchmarks need no asset files (boxes, capsules and spheres: scenegraph/MeshShapes.h).

#include <memory>
#include <vector>

#include <glm/gtc/type_precision.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "throng/scenegraph/Image.h"
#include "throng/scenegraph/MeshData.h"
#include "throng/scenegraph/MeshShapes.h"

namespace throng {

/// A `width` x `height` quad in the XY plane facing +Z, centred on the origin; texture coordinate
/// (0,0) is its top-left corner, so the image appears upright.
std::shared_ptr<MeshData> makeQuad(float width, float height, std::shared_ptr<const Image> texture = nullptr,
                                   const glm::vec4& color = glm::vec4(1.0f));

/// A `size` x `size` checkerboard of `cells` x `cells` squares, colour `a` in the top-left square.
std::shared_ptr<Image> makeCheckerImage(int size, int cells, const glm::u8vec4& a, const glm::u8vec4& b);

/// Shape of a skinned tube along +Y, standing on the origin.
struct SkinnedTubeOptions {
    int joints = 2;          ///< joints in a chain, evenly spaced: joint j at y = j * height / joints
    int bands = 1;           ///< separate rings of quads stacked along the tube (vertices are not
                             ///< shared between bands, like the seams of a real character mesh)
    int ringsPerBand = 17;   ///< rings of vertices per band (>= 2)
    int segments = 16;       ///< quads around the tube (>= 3)
    int influences = 4;      ///< joint influences per vertex: 4 or 8
    float radius = 0.25f;    ///< metres
    float height = 2.0f;     ///< metres
    float blend = 1.0f;      ///< reach of a joint's weight, in bone lengths from its bone's middle
    glm::vec4 color{1.0f};   ///< base colour
};

/// A tube of about CesiumMan's size: 19 joints, 3264 vertices, 4608 triangles.
SkinnedTubeOptions cesiumManSizedTube();

/// A skinned tube. Each vertex is weighted by the joints whose bones are nearest (tent-shaped
/// weights reaching `blend` bone lengths, the `influences` largest kept and normalised to sum 1).
/// Throws std::invalid_argument naming the bad option.
std::shared_ptr<MeshData> makeSkinnedTube(const SkinnedTubeOptions& options);

/// A palette posing the tube of `options`: every joint after the first bends by `anglePerJoint`
/// radians about Z and twists by `twistPerJoint` about the bone (Y). Writes options.joints
/// matrices to `palette` (resized; its capacity is reused).
void bendTubePalette(const SkinnedTubeOptions& options, float anglePerJoint, std::vector<glm::mat4>& palette,
                     float twistPerJoint = 0.0f);

}  // namespace throng
