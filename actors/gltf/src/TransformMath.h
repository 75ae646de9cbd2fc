#pragma once
// Internal: the matrix arithmetic the glTF loader shares between reading nodes and building
// templates: a transform split into translation, rotation and scale (and whether the split is
// exact) and composed back, and the one measure the builders take of points.

#include <vector>

#include <glm/gtc/quaternion.hpp>
#include "throng/scenegraph/MeshData.h"
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace throng::gltf {

using glm::dmat4;
using glm::dquat;
using glm::dvec3;

/// A transform split as T(t) R(r) S(s), and whether that split is exact (no shear).
struct Trs {
    dvec3 t{0.0};                   ///< translation
    dquat r{1.0, 0.0, 0.0, 0.0};    ///< rotation
    dvec3 s{1.0};                   ///< scale (a mirror is put on x)
    bool exact = true;              ///< no shear: T R S gives the matrix back
    bool uniform = true;            ///< s.x == s.y == s.z > 0 (up to rounding): folds into a joint
};

/// Splits an affine matrix into T R S; shear is lost (and `exact` false).
Trs decompose(const dmat4& m);
/// T(t) R(r) S(s).
dmat4 compose(const dvec3& t, const dquat& r, const dvec3& s);
/// Whether `m` is the identity within 1e-9 per element.
bool nearIdentity(const dmat4& m);
/// GltfLoadOptions::scale as a matrix: the implicit parent of every root node.
dmat4 uniformScale(double scale);
/// The largest distance of `points` from the origin (0 for none): a character's rest extent.
double restExtent(const std::vector<dvec3>& points);
/// Carries the morph targets of `mesh` (whose positions and normals are still untransformed) into
/// the frame `m` takes the mesh to: position offsets by its linear part, normal offsets by its
/// normal matrix scaled per vertex as the vertex's normal is, so that normalising the morphed,
/// transformed normal gives what transforming the morphed normal gives.
void transformMorphTargets(MeshData& mesh, const dmat4& m);

}  // namespace throng::gltf
