#pragma once
// Barycentric coordinates clamped to a triangle, as seed 003 §4.1.2 clamps the camera to its morphing
// cell: the nearest point of the triangle, found against its edges and corners. Clamping each weight to
// [0, 1] and renormalising is not the same: it moves a point outside the triangle along a line
// towards the centroid, not to the triangle's nearest point, so a view just outside a cell blends
// views the eye is far from.

#include <array>

#include <glm/vec3.hpp>

namespace throng {

/// The barycentric coordinates, with respect to the triangle `corners`, of the point of that
/// triangle nearest `point` (a point in the triangle's plane, or else first projected onto it
/// orthogonally): each >= 0, summing to 1. Inside, they are the point's own coordinates; beyond one
/// edge, those of its foot on that edge; beyond a corner, that corner's. A degenerate triangle (its
/// corners on a line or one point) gives the nearest point of its longest side.
std::array<float, 3> clampedBarycentric(const std::array<glm::vec3, 3>& corners, const glm::vec3& point);

}  // namespace throng
