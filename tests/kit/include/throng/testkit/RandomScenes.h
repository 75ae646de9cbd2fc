#pragma once
// Random scenes and cameras for property tests: reproducible from a seed, with nested transforms,
// LOD nodes and geometry of varied sizes.

#include <cstdint>
#include <memory>
#include <random>

#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"

namespace throng::testkit {

/// Shape of a random scene.
struct RandomSceneParams {
    int objects = 200;          ///< top-level objects
    double extent = 200.0;      ///< objects are placed in [-extent, extent]^3
    int maxDepth = 3;           ///< nesting depth of transforms below each object
    Vec3 origin{0.0};           ///< offset of the whole scene (to test far from the origin)
};

/// A random tree of Transforms, LODs and Geometry leaves.
std::shared_ptr<Group> buildRandomScene(std::mt19937_64& rng, const RandomSceneParams& params);
/// A random perspective camera looking into the region [origin - extent, origin + extent]^3.
Camera randomCamera(std::mt19937_64& rng, double extent, const Vec3& origin = Vec3(0.0));

}  // namespace throng::testkit
