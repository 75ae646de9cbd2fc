#include "TransformMath.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace throng::gltf {

Trs decompose(const dmat4& m) {
    Trs d;
    d.t = dvec3(m[3]);
    dvec3 c[3] = {dvec3(m[0]), dvec3(m[1]), dvec3(m[2])};
    d.s = dvec3(glm::length(c[0]), glm::length(c[1]), glm::length(c[2]));
    const double det = glm::dot(c[0], glm::cross(c[1], c[2]));
    if (det < 0) d.s.x = -d.s.x;  // a mirror: put it on x
    glm::dmat3 rot(1.0);
    for (int k = 0; k < 3; ++k)
        if (std::abs(d.s[k]) > 1e-12) rot[k] = c[k] / d.s[k];
    const double tol = 1e-5 * std::max({std::abs(d.s.x), std::abs(d.s.y), std::abs(d.s.z), 1e-12});
    d.exact = std::abs(glm::dot(c[0], c[1])) <= tol * std::abs(d.s.x) + 1e-12 &&
              std::abs(glm::dot(c[0], c[2])) <= tol * std::abs(d.s.x) + 1e-12 &&
              std::abs(glm::dot(c[1], c[2])) <= tol * std::abs(d.s.y) + 1e-12 && std::abs(det) > 1e-30;
    d.r = glm::normalize(glm::quat_cast(rot));
    d.uniform = d.exact && d.s.x > 0 && std::abs(d.s.x - d.s.y) <= tol && std::abs(d.s.x - d.s.z) <= tol;
    return d;
}

dmat4 compose(const dvec3& t, const dquat& r, const dvec3& s) {
    dmat4 m = glm::mat4_cast(r);
    m[0] *= s.x, m[1] *= s.y, m[2] *= s.z;
    m[3] = glm::dvec4(t, 1.0);
    return m;
}

bool nearIdentity(const dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (std::abs(m[c][r] - (c == r ? 1.0 : 0.0)) > 1e-9) return false;
    return true;
}

dmat4 uniformScale(double scale) { return glm::scale(dmat4(1.0), dvec3(scale)); }

double restExtent(const std::vector<dvec3>& points) {
    double far = 0;
    for (const dvec3& p : points) far = std::max(far, glm::length(p));
    return far;
}

void transformMorphTargets(MeshData& mesh, const dmat4& m) {
    const glm::dmat3 linear(m);
    const glm::dmat3 normal = glm::inverseTranspose(linear);
    for (MorphTarget& t : mesh.morphTargets) {
        for (glm::vec3& d : t.positions) d = glm::vec3(linear * dvec3(d));
        for (std::size_t v = 0; v < t.normals.size(); ++v) {
            const double len = glm::length(normal * dvec3(mesh.normals[v]));
            t.normals[v] = glm::vec3(normal * dvec3(t.normals[v]) / (len > 0.0 ? len : 1.0));
        }
    }
}

}  // namespace throng::gltf
