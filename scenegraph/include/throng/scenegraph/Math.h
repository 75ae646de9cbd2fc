#pragma once
// Vector and matrix types of the scenegraph. World-space state is double precision so that actors
// 10^7 m from the origin keep sub-millimetre accuracy; data sent to a GPU is made camera-relative.

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace throng {

using Vec3 = glm::dvec3;  ///< A point or direction in world or local space (metres).
using Vec4 = glm::dvec4;  ///< A homogeneous point or a plane (normal, offset).
using Mat4 = glm::dmat4;  ///< A column-major 4x4 transform.
using Quat = glm::dquat;  ///< A rotation.

}  // namespace throng
