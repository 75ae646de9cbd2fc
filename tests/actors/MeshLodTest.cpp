// Geometric LOD of loaded characters: meshoptimizer levels keep a subset of the vertices with their
// skin influences, report their error, reject bad shares; the loader builds the vaLod levels a
// scene asks for and scales files in other units.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <vector>
#include <tuple>

#include "throng/testkit/Assets.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/gltf/MeshSimplifier.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"

using namespace throng;

namespace {

const std::string kAssets = testkit::sharedAssets();

// A dense sphere with made-up influences that depend on the vertex, so each can be traced.
std::shared_ptr<MeshData> skinnedSphere() {
    auto m = makeSphere("ball", glm::vec3(0), 1.0f, 48, 24, glm::vec4(1));
    for (std::size_t v = 0; v < m->vertexCount(); ++v) {
        const auto j = static_cast<std::uint16_t>(v % 7);
        m->joints0.push_back({j, std::uint16_t(j + 1), 0, 0});
        const float w = 0.25f + 0.5f * float(v % 3) / 2.0f;
        m->weights0.push_back({w, 1.0f - w, 0.0f, 0.0f});
    }
    return m;
}

std::tuple<float, float, float> key(const glm::vec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

TEST(MeshSimplifier, KeepsASubsetOfTheVerticesWithTheirInfluences) {
    const auto full = skinnedSphere();
    std::multimap<std::tuple<float, float, float>, std::size_t> original;
    for (std::size_t v = 0; v < full->vertexCount(); ++v) original.emplace(key(full->positions[v]), v);

    const SimplifiedMesh s = simplifyMesh(*full, 0.2);
    ASSERT_TRUE(s.mesh);
    s.mesh->validate();
    EXPECT_GT(s.mesh->triangleCount(), 0u);
    EXPECT_LE(double(s.mesh->triangleCount()), 0.3 * double(full->triangleCount()));
    EXPECT_LT(s.mesh->vertexCount(), full->vertexCount());
    EXPECT_TRUE(std::isfinite(s.error));
    EXPECT_GT(s.error, 0.0);
    EXPECT_LT(s.error, 0.5);  // a fifth of a unit sphere's triangles still look like a ball
    ASSERT_EQ(s.mesh->joints0.size(), s.mesh->vertexCount());
    for (std::size_t v = 0; v < s.mesh->vertexCount(); ++v) {
        const auto [first, last] = original.equal_range(key(s.mesh->positions[v]));
        bool same = false;
        for (auto it = first; it != last; ++it)
            same = same || (full->joints0[it->second] == s.mesh->joints0[v] && full->weights0[it->second] == s.mesh->weights0[v]);
        EXPECT_TRUE(same) << "vertex " << v << " is not an original vertex with its influences";
    }
}

TEST(MeshSimplifier, AShareOfOneKeepsEveryTriangle) {
    const auto full = skinnedSphere();
    const SimplifiedMesh s = simplifyMesh(*full, 1.0);
    EXPECT_EQ(s.mesh->triangleCount(), full->triangleCount());
    EXPECT_EQ(s.error, 0.0);
}

TEST(MeshSimplifier, RejectsSharesOutsideZeroToOneNamingTheMesh) {
    const auto full = skinnedSphere();
    for (double bad : {0.0, -0.5, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
        try {
            simplifyMesh(*full, bad);
            ADD_FAILURE() << "share " << bad << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("'ball'"), std::string::npos) << e.what();
        }
    }
}

TEST(GltfLod, CesiumManGetsTheLevelsAskedFor) {
    GltfLoadOptions options;
    options.lodLevels = {{15.0, 1.0}, {35.0, 0.25}, {80.0, 0.08}, {std::numeric_limits<double>::infinity(), 0.025}};
    const CharacterAsset asset = loadCharacter(kAssets + "/characters/CesiumMan.glb", options);
    ASSERT_EQ(asset.characters.size(), 1u);
    const LoadedCharacter& c = asset.characters[0];
    const auto& levels = c.tmpl->rootGeometry().levels();
    ASSERT_EQ(levels.size(), 4u);
    ASSERT_EQ(c.lodErrors.size(), 4u);
    EXPECT_EQ(c.lodErrors[0], 0.0);
    std::size_t previous = std::numeric_limits<std::size_t>::max();
    for (std::size_t i = 0; i < levels.size(); ++i) {
        EXPECT_EQ(levels[i].skin, 0);
        const auto* mesh = dynamic_cast<const MeshDrawable*>(levels[i].drawable.get());
        ASSERT_NE(mesh, nullptr);
        EXPECT_TRUE(mesh->mesh().skinned());
        EXPECT_LT(mesh->mesh().triangleCount(), previous) << "level " << i;
        previous = mesh->mesh().triangleCount();
        if (i > 0) {
            EXPECT_GE(c.lodErrors[i], c.lodErrors[i - 1]) << "level " << i;
        }
        EXPECT_LT(c.lodErrors[i], 0.5) << "level " << i << " of a 1.5 m character";
    }
    // The coarsest level keeps about the share asked for (4672 triangles in the file).
    EXPECT_LE(previous, 4672u * 0.025 * 1.5);
}

TEST(GltfLod, AScaleTurnsCentimetresIntoMetres) {
    const std::string fox = kAssets + "/characters/Fox.glb";
    const double cm = loadCharacter(fox).primaryTemplate()->skeletonRootRadius();
    GltfLoadOptions options;
    options.scale = 0.01;
    const double m = loadCharacter(fox, options).primaryTemplate()->skeletonRootRadius();
    EXPECT_GT(cm, 50.0);
    // The sampled part scales; the margin is the larger of 5 cm and 1% of the extent either way.
    EXPECT_NEAR(m, cm * 0.01, 0.06);
}

TEST(GltfLod, BadOptionsAreErrors) {
    const std::string fox = kAssets + "/characters/Fox.glb";
    GltfLoadOptions options;
    options.scale = 0.0;
    EXPECT_THROW(loadCharacter(fox, options), GltfError);
    options.scale = 1.0;
    options.lodLevels = {{20.0, 1.0}, {10.0, 0.5}};
    EXPECT_THROW(loadCharacter(fox, options), GltfError);
    options.lodLevels = {{20.0, 0.0}};
    EXPECT_THROW(loadCharacter(fox, options), GltfError);
}

TEST(GltfLod, SmallPartsSwitchOffNearerThanTheLimbsHoldingThem) {
    GltfLoadOptions options;
    options.scale = 0.36;
    options.jointMinAngle = 0.004;
    const auto robot = loadCharacter(kAssets + "/characters/robot.glb", options).primaryTemplate();
    const auto nodes = robot->nodes();
    std::size_t finite = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const double d = nodes[i].deactivationDistance;
        EXPECT_GT(d, 0.0) << nodes[i].name;
        finite += std::isfinite(d);
        if (nodes[i].parent >= 0) {
            EXPECT_LE(d, nodes[std::size_t(nodes[i].parent)].deactivationDistance) << nodes[i].name;
        }
    }
    std::size_t roots = 0;
    for (const auto& n : nodes) roots += n.parent < 0;
    EXPECT_GE(roots, 1u);
    // The robot has no rigid part: every joint but the roots may switch off.
    EXPECT_EQ(finite, nodes.size() - roots);
    const int finger = robot->findNode("Index2.L"), arm = robot->findNode("UpperArm.L");
    ASSERT_GE(finger, 0);
    ASSERT_GE(arm, 0);
    // A finger segment of a few centimetres goes long before the whole arm.
    EXPECT_LT(nodes[std::size_t(finger)].deactivationDistance * 4.0, nodes[std::size_t(arm)].deactivationDistance);
    EXPECT_LT(nodes[std::size_t(finger)].deactivationDistance, 40.0);
    // Off by default.
    const auto full = loadCharacter(kAssets + "/characters/robot.glb").primaryTemplate();
    for (const auto& n : full->nodes()) EXPECT_TRUE(std::isinf(n.deactivationDistance)) << n.name;
}

// With a wide angle, far away, every joint may switch off but the roots: the switched-off joints
// then follow a root, which carries the template's scale (the Fox's 0.01). With no active joint at
// all the skin fell back to its bind space, a hundred times too large.
TEST(GltfLod, FarAwayTheRootsStayOnSoTheSkinKeepsItsScale) {
    GltfLoadOptions options;
    options.jointMinAngle = 0.016;
    const auto fox = loadCharacter(kAssets + "/characters/Fox.glb", options).primaryTemplate();
    std::vector<std::uint8_t> active(fox->nodeCount());
    const double far = 10000.0;
    computeActiveNodes(*fox, far * far, active);
    std::size_t on = 0;
    for (std::size_t i = 0; i < fox->nodeCount(); ++i) {
        if (fox->nodes()[i].parent < 0) {
            EXPECT_TRUE(active[i]) << fox->nodes()[i].name;
        }
        on += active[i];
    }
    EXPECT_LT(on, fox->nodeCount() / 2) << "most joints are off that far";
}
