// The glTF loader on documents written here: joints become Skeleton nodes with Position,
// Orientation and Scale DOFs; non-joint nodes fold exactly into the joint below; STEP and
// CUBICSPLINE sample as the glTF specification says; sparse accessors substitute; and every bad
// input is an error naming its JSON pointer.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "throng/testkit/GltfTestFile.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/scenegraph/MeshDrawable.h"

using namespace throng;
using namespace throng::testkit;
using J = nlohmann::json;

namespace {

CharacterAsset load(const GltfTestFile& f, const GltfLoadOptions& o = {}) { return loadCharacterFromMemory(f.bytes(), "test.gltf", o); }

// The JSON pointer of the error loading `f` gives, or "(loaded)".
std::string errorWhere(const std::vector<std::uint8_t>& bytes, const GltfLoadOptions& o = {}) {
    try {
        loadCharacterFromMemory(bytes, "bad.gltf", o);
    } catch (const GltfError& e) {
        return e.where();
    }
    return "(loaded)";
}
std::string errorWhere(const GltfTestFile& f) { return errorWhere(f.bytes()); }

bool hasWarning(const CharacterAsset& a, const std::string& text) {
    for (const auto& w : a.warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

// Model matrices of a template with `dofs`.
std::vector<Affine> modelOf(const ActorTemplate& t, std::span<const float> dofs) {
    std::vector<Affine> m(t.nodeCount());
    computeModelTransforms(t, dofs, {}, m);
    return m;
}

void expectNear(const Mat4& a, const Mat4& b, double tol) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tol) << "element [" << c << "][" << r << "]";
}

}  // namespace

TEST(Gltf, JointsBecomeSkeletonNodesWithPositionOrientationScaleDofsAtTheirRest) {
    GltfTestFile f = twoJointRig();
    f.doc["nodes"][1]["rotation"] = {0, 0, std::sin(0.25), std::cos(0.25)};
    f.doc["nodes"][1]["scale"] = {2, 2, 2};
    const CharacterAsset a = load(f);
    ASSERT_EQ(a.characters.size(), 1u);
    const LoadedCharacter& c = a.characters[0];
    EXPECT_EQ(c.skin, 0);
    EXPECT_EQ(c.jointCount, 2);
    EXPECT_EQ(c.nodeSource, (std::vector<int>{0, 1}));
    const ActorTemplate& t = *c.tmpl;
    EXPECT_EQ(t.name(), "test");
    ASSERT_EQ(t.nodeCount(), 2u);
    EXPECT_EQ(t.nodes()[0].name, "hip");
    EXPECT_EQ(t.nodes()[1].name, "knee");
    EXPECT_EQ(t.nodes()[1].parent, 0);
    for (const SkeletonNode& n : t.nodes()) {
        ASSERT_EQ(n.dofs.size(), 3u);
        EXPECT_EQ(n.dofs[0].kind, DofKind::Position);
        EXPECT_EQ(n.dofs[1].kind, DofKind::Orientation);
        EXPECT_EQ(n.dofs[2].kind, DofKind::Scale);
        EXPECT_TRUE(std::isinf(n.deactivationDistance));
    }
    const Dof& knee = t.nodes()[1].dofs[1];
    EXPECT_NEAR(knee.rest[2], std::sin(0.25), 1e-6);
    EXPECT_NEAR(knee.rest[3], std::cos(0.25), 1e-6);
    EXPECT_FLOAT_EQ(t.nodes()[1].dofs[0].rest[1], 0.5f);
    EXPECT_FLOAT_EQ(t.nodes()[1].dofs[2].rest[0], 2.0f);
    ASSERT_EQ(t.skins().size(), 1u);
    EXPECT_EQ(t.skins()[0].joints, (std::vector<std::uint32_t>{0, 1}));
    EXPECT_FLOAT_EQ(t.nodes()[1].inverseBind[3][1], -1.5f);
    // The skinned mesh is a level of the actor's vaLod; the joints' spheres bound their vertices.
    ASSERT_EQ(t.rootGeometry().levels().size(), 1u);
    EXPECT_EQ(t.rootGeometry().levels()[0].skin, 0);
    EXPECT_TRUE(t.nodes()[0].geometrySphere.valid());
    EXPECT_TRUE(t.nodes()[1].geometrySphere.valid());
    ASSERT_EQ(a.primitives.size(), 1u);
    EXPECT_EQ(a.primitives[0].skin, 0);
    EXPECT_EQ(a.primitives[0].data->triangleCount(), 2u);
    EXPECT_EQ(a.primaryTemplate(), c.tmpl);
    EXPECT_EQ(a.findCharacter("test"), &a.characters[0]);
    EXPECT_EQ(a.findCharacter("nobody"), nullptr);
}

TEST(Gltf, MatrixJointsAreDecomposed) {
    GltfTestFile f = twoJointRig();
    f.doc["nodes"][1].erase("translation");
    // 90 degrees about Y, scale 3, translation (1, 2, 3), column-major.
    f.doc["nodes"][1]["matrix"] = {0, 0, -3, 0, 0, 3, 0, 0, 3, 0, 0, 0, 1, 2, 3, 1};
    const auto t = load(f).characters[0].tmpl;
    const auto& d = t->nodes()[1].dofs;
    EXPECT_NEAR(d[0].rest[0], 1, 1e-6);
    EXPECT_NEAR(d[0].rest[2], 3, 1e-6);
    EXPECT_NEAR(d[2].rest[1], 3, 1e-5);
    const glm::quat q(d[1].rest[3], d[1].rest[0], d[1].rest[1], d[1].rest[2]);
    EXPECT_NEAR(std::abs(q.y), std::sqrt(0.5), 1e-5);
}

TEST(Gltf, NonJointNodesAboveFoldExactlyIntoTheJointAndItsTranslationChannel) {
    GltfTestFile f = twoJointRig();
    // Z-up armature above the hip: translation, 90 degrees about X, uniform scale 0.01.
    const double h = std::sqrt(0.5);
    const int arm = f.push("nodes", {{"name", "Armature"}, {"translation", {1, 2, 3}}, {"rotation", {h, 0, 0, h}},
                                     {"scale", {0.01, 0.01, 0.01}}, {"children", J::array({0})}});
    f.doc["scenes"][0]["nodes"] = J::array({arm, 2});
    animate(f, 0, "translation", "LINEAR", {0, 1}, {0, 100, 0, 0, 200, 50}, "VEC3");
    const CharacterAsset a = load(f);
    const ActorTemplate& t = *a.characters[0].tmpl;
    ASSERT_EQ(t.nodeCount(), 2u);  // the armature left no node of its own
    const glm::dmat4 armature = glm::translate(glm::dmat4(1), glm::dvec3(1, 2, 3)) *
                                glm::mat4_cast(glm::dquat(h, h, 0, 0)) * glm::scale(glm::dmat4(1), glm::dvec3(0.01));
    // Rest: model transforms are the glTF world matrices.
    auto m = modelOf(t, t.restDofs());
    expectNear(m[0].toDMat4(), armature * glm::translate(glm::dmat4(1), glm::dvec3(0, 1, 0)), 1e-6);
    // Animated at t = 0.5: hip translated by (0, 150, 25) in the armature's frame.
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    t.clips()[0]->sample(t, 0.5, false, {}, dofs);
    m = modelOf(t, dofs);
    const glm::dmat4 hip = armature * glm::translate(glm::dmat4(1), glm::dvec3(0, 150, 25));
    expectNear(m[0].toDMat4(), hip, 1e-5);
    expectNear(m[1].toDMat4(), hip * glm::translate(glm::dmat4(1), glm::dvec3(0, 0.5, 0)), 1e-5);
}

TEST(Gltf, NonUniformScaleAboveAJointBecomesADoflessNodeWithAWarning) {
    GltfTestFile f = twoJointRig();
    const int arm = f.push("nodes", {{"name", "Stretch"}, {"scale", {1, 2, 1}}, {"children", J::array({0})}});
    f.doc["scenes"][0]["nodes"] = J::array({arm, 2});
    const CharacterAsset a = load(f);
    const ActorTemplate& t = *a.characters[0].tmpl;
    ASSERT_EQ(t.nodeCount(), 3u);
    EXPECT_EQ(t.nodes()[0].name, "Stretch");
    EXPECT_TRUE(t.nodes()[0].dofs.empty());
    EXPECT_EQ(a.characters[0].jointCount, 2);
    EXPECT_EQ(t.skins()[0].joints, (std::vector<std::uint32_t>{1, 2}));
    EXPECT_TRUE(hasWarning(a, "non-uniform scale"));
    const auto m = modelOf(t, t.restDofs());
    expectNear(m[2].toDMat4(), glm::scale(glm::dmat4(1), glm::dvec3(1, 2, 1)) * glm::translate(glm::dmat4(1), glm::dvec3(0, 1.5, 0)), 1e-6);
}

// An animated node above the skeleton (an armature carrying root motion) moves the joints: glTF
// defines a joint's global transform through its ancestors. It becomes a Skeleton node with DOFs
// (not a skin joint) instead of being folded as a constant, and its channels are loaded.
TEST(Gltf, AnimatedNodeAboveTheSkeletonMovesTheSkin) {
    GltfTestFile f = twoJointRig();
    const int arm = f.push("nodes", {{"name", "Armature"}, {"translation", {1, 2, 3}}, {"scale", {0.5, 0.5, 0.5}},
                                     {"children", J::array({0})}});
    f.doc["scenes"][0]["nodes"] = J::array({arm, 2});
    const double h = std::sqrt(0.5);
    const int times = f.floats({0, 1}, "SCALAR");
    f.doc["accessors"][std::size_t(times)]["min"] = {0};
    f.doc["accessors"][std::size_t(times)]["max"] = {1};
    const int moves = f.floats({1, 2, 3, 3, 2, 3}, "VEC3");
    const int turns = f.floats({0, 0, 0, 1, 0, float(h), 0, float(h)}, "VEC4");  // 0 -> 90 degrees about Y
    f.push("animations", {{"name", "walk"},
                          {"samplers", J::array({{{"input", times}, {"output", moves}}, {{"input", times}, {"output", turns}}})},
                          {"channels", J::array({{{"sampler", 0}, {"target", {{"node", arm}, {"path", "translation"}}}},
                                                 {{"sampler", 1}, {"target", {{"node", arm}, {"path", "rotation"}}}}})}});
    GltfLoadOptions options;
    options.scale = 2.0;  // folded into the armature's Skeleton node as into a joint
    const CharacterAsset a = load(f, options);
    EXPECT_FALSE(hasWarning(a, "not a joint"));
    const LoadedCharacter& c = a.characters[0];
    const ActorTemplate& t = *c.tmpl;
    ASSERT_EQ(t.nodeCount(), 3u);
    EXPECT_EQ(t.nodes()[0].name, "Armature");
    EXPECT_EQ(t.nodes()[0].dofs.size(), 3u);
    EXPECT_EQ(c.nodeSource, (std::vector<int>{arm, 0, 1}));
    EXPECT_EQ(c.jointCount, 2);
    EXPECT_EQ(t.skins()[0].joints, (std::vector<std::uint32_t>{1, 2}));
    EXPECT_EQ(a.animations[0].channelsLoaded, 2);
    ASSERT_EQ(t.clips().size(), 1u);
    // At t = 0.5 the armature stands at (2, 2, 3), turned by 45 degrees about Y.
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    t.clips()[0]->sample(t, 0.5, false, {}, dofs);
    const auto m = modelOf(t, dofs);
    const glm::dmat4 armature = glm::scale(glm::dmat4(1), glm::dvec3(2.0)) * glm::translate(glm::dmat4(1), glm::dvec3(2, 2, 3)) *
                                glm::rotate(glm::dmat4(1), std::numbers::pi / 4, glm::dvec3(0, 1, 0)) *
                                glm::scale(glm::dmat4(1), glm::dvec3(0.5));
    expectNear(m[1].toDMat4(), armature * glm::translate(glm::dmat4(1), glm::dvec3(0, 1, 0)), 1e-5);
    expectNear(m[2].toDMat4(), armature * glm::translate(glm::dmat4(1), glm::dvec3(0, 1.5, 0)), 1e-5);
    // And the skin follows: hip's skinning matrix is its model transform times its inverse bind.
    std::vector<glm::mat4> palette(2);
    computeSkinPalette(t, t.skins()[0], m, {}, palette);
    expectNear(glm::dmat4(palette[0]), armature, 1e-5);  // the hip is bound at (0, 1, 0)
}

TEST(Gltf, StepHoldsThePreviousKeyAndClipEndsClamp) {
    GltfTestFile f = twoJointRig();
    animate(f, 1, "translation", "STEP", {0, 1, 2}, {0, 0, 0, 1, 0, 0, 2, 0, 0}, "VEC3");
    const CharacterAsset a = load(f);
    const ActorTemplate& t = *a.characters[0].tmpl;
    ASSERT_EQ(t.clips().size(), 1u);
    const auto& clip = *t.clips()[0];
    EXPECT_EQ(clip.channels()[0].interpolation, Interpolation::Step);
    EXPECT_DOUBLE_EQ(clip.duration(), 2.0);
    auto x = [&](double time, bool loop) {
        std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
        clip.sample(t, time, loop, {}, dofs);
        return dofs[t.dofValueOffset(1, 0)];
    };
    EXPECT_FLOAT_EQ(x(0.5, false), 0.0f);
    EXPECT_FLOAT_EQ(x(0.999, false), 0.0f);
    EXPECT_FLOAT_EQ(x(1.0, false), 1.0f);
    EXPECT_FLOAT_EQ(x(1.5, false), 1.0f);
    EXPECT_FLOAT_EQ(x(2.0, false), 2.0f);
    EXPECT_FLOAT_EQ(x(7.0, false), 2.0f);  // clamped past the end
    EXPECT_FLOAT_EQ(x(3.5, true), 1.0f);   // looped: 1.5 s
    EXPECT_EQ(a.animations[0].channels, 1);
    EXPECT_EQ(a.animations[0].channelsLoaded, 1);
}

TEST(Gltf, CubicSplineMatchesTheHandComputedHermiteValue) {
    GltfTestFile f = twoJointRig();
    // Keys at 0 and 2 s; per key: in-tangent, value, out-tangent (glTF order).
    animate(f, 1, "translation", "CUBICSPLINE", {0, 2},
            {9, 9, 9, 0, 0, 0, 1, 0, 0,  // key 0: value 0, out-tangent (1, 0, 0)
             0.5f, 0, 0, 1, 0, 0, 9, 9, 9},  // key 1: in-tangent (0.5, 0, 0), value 1
            "VEC3");
    const CharacterAsset a = load(f);
    const ActorTemplate& t = *a.characters[0].tmpl;
    const auto& clip = *t.clips()[0];
    EXPECT_EQ(clip.channels()[0].interpolation, Interpolation::CubicSpline);
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    clip.sample(t, 1.0, false, {}, dofs);
    // u = 0.5, dt = 2: h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = -0.125
    // x = 0.5 * 0 + 0.125 * 2 * 1 + 0.5 * 1 - 0.125 * 2 * 0.5 = 0.625
    EXPECT_NEAR(dofs[t.dofValueOffset(1, 0)], 0.625f, 1e-6);
    clip.sample(t, 0.5, false, {}, dofs);
    // u = 0.25: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875
    // x = 0.140625 * 2 + 0.15625 - 0.046875 * 2 * 0.5 = 0.390625
    EXPECT_NEAR(dofs[t.dofValueOffset(1, 0)], 0.390625f, 1e-6);
    clip.sample(t, 2.0, false, {}, dofs);
    EXPECT_FLOAT_EQ(dofs[t.dofValueOffset(1, 0)], 1.0f);
}

TEST(Gltf, ClipsEndAtTheirLastKeyAndShortChannelsHold) {
    GltfTestFile f = twoJointRig();
    const int t1 = f.floats({0, 1}, "SCALAR"), t2 = f.floats({0, 2}, "SCALAR");
    const int v1 = f.floats({0, 0, 0, 1, 0, 0}, "VEC3"), v2 = f.floats({0, 0, 0, 1, 0, 0}, "VEC3");
    f.push("animations", {{"name", "two"},
                          {"samplers", J::array({J{{"input", t1}, {"output", v1}}, J{{"input", t2}, {"output", v2}}})},
                          {"channels", J::array({J{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}},
                                                 J{{"sampler", 1}, {"target", {{"node", 1}, {"path", "translation"}}}}})}});
    const CharacterAsset a = load(f);
    const ActorTemplate& t = *a.characters[0].tmpl;
    const auto& clip = *t.clips()[0];
    EXPECT_EQ(clip.name(), "two");
    EXPECT_DOUBLE_EQ(clip.duration(), 2.0);
    EXPECT_DOUBLE_EQ(a.animations[0].duration, 2.0);
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    clip.sample(t, 1.5, false, {}, dofs);
    EXPECT_FLOAT_EQ(dofs[t.dofValueOffset(0, 0)], 1.0f);   // ended at 1 s: holds its last key
    EXPECT_FLOAT_EQ(dofs[t.dofValueOffset(1, 0)], 0.75f);  // still running
    EXPECT_EQ(a.characters[0].clipSource, (std::vector<int>{0}));
}

TEST(Gltf, SparseAccessorsSubstituteTheirValues) {
    GltfTestFile f = twoJointRig();
    // POSITION of the quad with vertex 2 replaced by (5, 6, 7) through a sparse substitution.
    const std::uint16_t which[] = {2};
    const float values[] = {5, 6, 7};
    const int iv = f.view(which, sizeof which), vv = f.view(values, sizeof values);
    J& pos = f.doc["accessors"][0];
    pos["sparse"] = {{"count", 1}, {"indices", {{"bufferView", iv}, {"componentType", 5123}}}, {"values", {{"bufferView", vv}}}};
    CharacterAsset a = load(f);
    const MeshData& m = *a.primitives[0].data;
    EXPECT_EQ(m.positions[2], glm::vec3(5, 6, 7));
    EXPECT_EQ(m.positions[1], glm::vec3(0.1f, 0.5f, 0));
    // Without a buffer view the base is zeros.
    pos.erase("bufferView");
    a = load(f);
    EXPECT_EQ(a.primitives[0].data->positions[2], glm::vec3(5, 6, 7));
    EXPECT_EQ(a.primitives[0].data->positions[1], glm::vec3(0));
}

TEST(Gltf, UnskinnedMeshesAreInWorldSpaceAndBelowJointsTheyAreRigidGeometry) {
    GltfTestFile f = twoJointRig();
    const int pos = f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    f.push("meshes", {{"name", "hat"}, {"primitives", J::array({J{{"attributes", {{"POSITION", pos}}}}})}});
    const int hat = f.push("nodes", {{"name", "hat"}, {"mesh", 1}, {"translation", {0, 0.25, 0}}});
    f.doc["nodes"][1]["children"] = J::array({hat});
    const int box = f.push("nodes", {{"name", "box"}, {"mesh", 1}, {"translation", {10, 0, 0}}, {"scale", {1, 1, -1}}});
    f.doc["scenes"][0]["nodes"].push_back(box);
    const CharacterAsset a = load(f);
    ASSERT_EQ(a.characters.size(), 2u);
    EXPECT_EQ(a.characters[1].tmpl->name(), "test/static");
    ASSERT_EQ(a.primitives.size(), 3u);
    // Scene order, depth first: the hat (below the knee), the body, the box.
    EXPECT_EQ(a.primitives[0].node, hat);
    EXPECT_EQ(a.primitives[1].skin, 0);
    EXPECT_EQ(a.primitives[2].node, box);
    // World space: the hat sits at knee (0, 1.5, 0) + 0.25; the box is mirrored (winding flipped).
    EXPECT_EQ(a.primitives[0].data->positions[0], glm::vec3(0, 1.75f, 0));
    EXPECT_EQ(a.primitives[2].data->positions[1], glm::vec3(11, 0, 0));
    EXPECT_EQ(a.primitives[2].data->indices, (std::vector<std::uint32_t>{0, 2, 1}));
    // The hat is drawn by a DOF-less child of the knee, in the knee's frame.
    const ActorTemplate& t = *a.characters[0].tmpl;
    ASSERT_EQ(t.nodeCount(), 3u);
    EXPECT_EQ(t.nodes()[2].parent, 1);
    EXPECT_TRUE(t.nodes()[2].dofs.empty());
    EXPECT_EQ(t.nodes()[2].geometry.levels().size(), 1u);
    EXPECT_TRUE(t.nodes()[2].geometry.bound().contains(Vec3(0, 0.25, 0)));
}

// Found by the fuzzer: a finite vertex that a node's scale carries beyond float range. The error
// names the positions and the node, instead of a bad vertex found later.
TEST(Gltf, AVertexPlacedBeyondFloatRangeIsAnErrorNamingItsPositions) {
    GltfTestFile f = twoJointRig();
    const int pos = f.floats({0, 0, 0, 1e37f, 0, 0, 0, 1, 0}, "VEC3");
    f.push("meshes", {{"name", "hat"}, {"primitives", J::array({J{{"attributes", {{"POSITION", pos}}}}})}});
    const int hat = f.push("nodes", {{"name", "hat"}, {"mesh", 1}, {"scale", {100, 100, 100}}});
    f.doc["nodes"][1]["children"] = J::array({hat});
    try {
        (void)load(f);
        FAIL() << "a vertex beyond float range loaded";
    } catch (const GltfError& e) {
        EXPECT_EQ(e.where(), "/meshes/1/primitives/0/attributes/POSITION");
        EXPECT_NE(e.problem().find("vertex 1 lies beyond float range once placed by node " + std::to_string(hat)), std::string::npos)
            << e.problem();
    }
}

// A primitive below a joint is drawn by the skin's template only: the static template takes the
// unskinned primitives no skin claimed, each exactly once.
TEST(Gltf, EachUnskinnedPrimitiveIsDrawnByExactlyOneTemplate) {
    GltfTestFile f = twoJointRig();
    const int pos = f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    f.push("meshes", {{"name", "hat"}, {"primitives", J::array({J{{"attributes", {{"POSITION", pos}}}}})}});
    const int hat = f.push("nodes", {{"name", "hat"}, {"mesh", 1}});
    f.doc["nodes"][1]["children"] = J::array({hat});
    const int box = f.push("nodes", {{"name", "box"}, {"mesh", 1}});
    f.doc["scenes"][0]["nodes"].push_back(box);
    const CharacterAsset a = load(f);
    ASSERT_EQ(a.primitives.size(), 3u);  // the hat, the body, the box
    ASSERT_EQ(a.characters.size(), 2u);
    EXPECT_EQ(a.characters[0].primitives, (std::vector<int>{0, 1}));  // the hat as the knee's geometry, then the body
    EXPECT_EQ(a.characters[1].primitives, (std::vector<int>{2}));     // the box only
    EXPECT_EQ(a.characters[1].tmpl->nodeCount(), 1u);
}

TEST(Gltf, SeveralColoursOnOneSkinBecomeAPaletteTexture) {
    GltfTestFile f = twoJointRig();
    f.push("materials", {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}});
    f.push("materials", {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 1, 1}}}}});
    J prim = f.doc["meshes"][0]["primitives"][0];
    prim["material"] = 0;
    f.doc["meshes"][0]["primitives"][0]["material"] = 1;
    f.doc["meshes"][0]["primitives"].push_back(prim);
    const CharacterAsset a = load(f);
    const auto& level = a.characters[0].tmpl->rootGeometry().levels()[0];
    const MeshData& m = dynamic_cast<const MeshDrawable&>(*level.drawable).mesh();
    EXPECT_EQ(m.triangleCount(), 4u);
    ASSERT_TRUE(m.baseColorTexture);
    EXPECT_EQ(m.baseColorTexture->width, 2);
    EXPECT_EQ(m.texcoords.size(), m.vertexCount());
    EXPECT_EQ(m.baseColor, glm::vec4(1));
}

TEST(Gltf, ErrorsNameFileWhereAndProblemOnOneLine) {
    GltfTestFile f = twoJointRig();
    f.doc["skins"][0]["joints"][1] = 17;
    try {
        loadCharacterFromMemory(f.bytes(), "rig.gltf");
        FAIL() << "no error";
    } catch (const GltfError& e) {
        EXPECT_EQ(e.file(), "rig.gltf");
        EXPECT_EQ(e.where(), "/skins/0/joints/1");
        EXPECT_EQ(std::string(e.what()), "rig.gltf: /skins/0/joints/1: " + e.problem());
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
}

// Each case breaks the rig one way; the error must point at the culprit.
TEST(Gltf, BadInputsAreErrorsAtTheirJsonPointer) {
    struct Case {
        const char* name;
        std::function<void(GltfTestFile&)> breakIt;
        std::string where;
    };
    const float nan = std::nanf("");
    const std::vector<Case> cases = {
        {"joint index beyond the skin", [](GltfTestFile& f) { f.doc["accessors"][1]["bufferView"] = f.view(std::vector<std::uint16_t>(16, 5).data(), 32); },
         "/meshes/0/primitives/0/attributes/JOINTS_0"},
        {"NaN position", [&](GltfTestFile& f) { f.doc["accessors"][0]["bufferView"] = f.view(std::vector<float>(12, nan).data(), 48); }, "/accessors/0"},
        {"accessor past its view", [](GltfTestFile& f) { f.doc["accessors"][0]["count"] = 5; }, "/accessors/0"},
        {"view past its buffer", [](GltfTestFile& f) { f.doc["bufferViews"][0]["byteLength"] = 4096; }, "/bufferViews/0"},
        {"stride smaller than an element", [](GltfTestFile& f) { f.doc["bufferViews"][0]["byteStride"] = 8; }, "/bufferViews/0/byteStride"},
        {"index beyond the vertices", [](GltfTestFile& f) { f.doc["accessors"][3]["bufferView"] = f.view(std::vector<std::uint16_t>{0, 1, 9, 0, 0, 0}.data(), 12); },
         "/meshes/0/primitives/0/indices"},
        {"missing accessor", [](GltfTestFile& f) { f.doc["meshes"][0]["primitives"][0]["indices"] = 99; }, "/meshes/0/primitives/0/indices"},
        {"bad component type", [](GltfTestFile& f) { f.doc["accessors"][0]["componentType"] = 5124; }, "/accessors/0/componentType"},
        {"child out of range", [](GltfTestFile& f) { f.doc["nodes"][0]["children"] = J::array({42}); }, "/nodes/0/children/0"},
        {"two parents", [](GltfTestFile& f) { f.doc["nodes"][2]["children"] = J::array({1}); }, "/nodes/2/children/0"},
        {"cycle", [](GltfTestFile& f) { f.doc["nodes"][1]["children"] = J::array({0}); f.doc["scenes"][0]["nodes"] = J::array({2}); }, "/nodes/0"},
        {"mesh out of range", [](GltfTestFile& f) { f.doc["nodes"][2]["mesh"] = 3; }, "/nodes/2/mesh"},
        {"skin out of range", [](GltfTestFile& f) { f.doc["nodes"][2]["skin"] = 3; }, "/nodes/2/skin"},
        {"material out of range", [](GltfTestFile& f) { f.doc["meshes"][0]["primitives"][0]["material"] = 0; }, "/meshes/0/primitives/0/material"},
        {"zero quaternion", [](GltfTestFile& f) { f.doc["nodes"][0]["rotation"] = {0, 0, 0, 0}; }, "/nodes/0/rotation"},
        {"projective matrix", [](GltfTestFile& f) { f.doc["nodes"][0].erase("translation"); f.doc["nodes"][0]["matrix"] = {1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
         "/nodes/0/matrix"},
        {"scene root with a parent", [](GltfTestFile& f) { f.doc["scenes"][0]["nodes"] = J::array({1}); }, "/scenes/0/nodes/0"},
        {"missing scene", [](GltfTestFile& f) { f.doc["scene"] = 4; }, "/scene"},
        {"duplicate joint", [](GltfTestFile& f) { f.doc["skins"][0]["joints"] = J::array({0, 0}); }, "/skins/0/joints/1"},
        {"skin joints not a list", [](GltfTestFile& f) { f.doc["skins"][0]["joints"] = 3; }, "/skins/0/joints"},
        {"IBM not affine", [](GltfTestFile& f) {
             std::vector<float> m(32, 0.0f);
             m[3] = 1;
             f.doc["accessors"][4]["bufferView"] = f.view(m.data(), 128); },
         "/skins/0/inverseBindMatrices"},
        {"weights without joints", [](GltfTestFile& f) { f.doc["meshes"][0]["primitives"][0]["attributes"].erase("JOINTS_0"); },
         "/meshes/0/primitives/0/attributes/JOINTS_0"},
        {"negative weight", [](GltfTestFile& f) { f.doc["accessors"][2]["bufferView"] = f.view(std::vector<float>(16, -1.0f).data(), 64); },
         "/meshes/0/primitives/0/attributes/WEIGHTS_0"},
        {"normal count differs", [](GltfTestFile& f) { f.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = f.floats({0, 1, 0}, "VEC3"); },
         "/meshes/0/primitives/0/attributes/NORMAL"},
        {"times decreasing", [](GltfTestFile& f) { animate(f, 1, "translation", "LINEAR", {1, 0}, {0, 0, 0, 1, 1, 1}, "VEC3"); },
         "/animations/0/samplers/0/input"},
        {"negative time", [](GltfTestFile& f) { animate(f, 1, "translation", "LINEAR", {-1, 0}, {0, 0, 0, 1, 1, 1}, "VEC3"); },
         "/animations/0/samplers/0/input"},
        {"clip too long", [](GltfTestFile& f) { animate(f, 1, "translation", "LINEAR", {0, 1e9f}, {0, 0, 0, 1, 1, 1}, "VEC3"); },
         "/animations/0/samplers/0/input"},
        {"unknown interpolation", [](GltfTestFile& f) { animate(f, 1, "translation", "BEZIER", {0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3"); },
         "/animations/0/samplers/0/interpolation"},
        {"output count", [](GltfTestFile& f) { animate(f, 1, "translation", "CUBICSPLINE", {0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3"); },
         "/animations/0/samplers/0/output"},
        {"rotation of width 3", [](GltfTestFile& f) { animate(f, 1, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3"); },
         "/animations/0/samplers/0/output"},
        {"zero rotation key", [](GltfTestFile& f) { animate(f, 1, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0, 0, 0}, "VEC4"); },
         "/animations/0/channels/0"},
        {"target node out of range", [](GltfTestFile& f) { animate(f, 9, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0, 0, 1}, "VEC4"); },
         "/animations/0/channels/0/target/node"},
        {"sparse indices not increasing", [](GltfTestFile& f) {
             const std::uint16_t idx[] = {2, 1};
             const float v[] = {0, 0, 0, 0, 0, 0};
             const int iv = f.view(idx, 4), vv = f.view(v, 24);
             f.doc["accessors"][0]["sparse"] = {{"count", 2}, {"indices", {{"bufferView", iv}, {"componentType", 5123}}}, {"values", {{"bufferView", vv}}}}; },
         "/accessors/0/sparse/indices"},
        {"sparse index beyond count", [](GltfTestFile& f) {
             const std::uint16_t idx[] = {7, 0};
             const float v[] = {0, 0, 0};
             const int iv = f.view(idx, 2), vv = f.view(v, 12);
             f.doc["accessors"][0]["sparse"] = {{"count", 1}, {"indices", {{"bufferView", iv}, {"componentType", 5123}}}, {"values", {{"bufferView", vv}}}}; },
         "/accessors/0/sparse/indices"},
        {"sparse values past the view", [](GltfTestFile& f) {
             const std::uint16_t idx[] = {1, 2};
             const float v[] = {0, 0, 0};
             const int iv = f.view(idx, 4), vv = f.view(v, 12);
             f.doc["accessors"][0]["sparse"] = {{"count", 2}, {"indices", {{"bufferView", iv}, {"componentType", 5123}}}, {"values", {{"bufferView", vv}}}}; },
         "/accessors/0/sparse/values"},
        {"attribute accessor out of range", [](GltfTestFile& f) { f.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 77; },
         "/meshes/0/primitives/0/attributes/NORMAL"},
    };
    for (const Case& c : cases) {
        GltfTestFile f = twoJointRig();
        c.breakIt(f);
        EXPECT_EQ(errorWhere(f), c.where) << c.name;
    }
}

TEST(Gltf, MalformedDocumentsAndContainersAreErrorsAtTheRoot) {
    auto bytes = [](const std::string& s) { return std::vector<std::uint8_t>(s.begin(), s.end()); };
    EXPECT_EQ(errorWhere(bytes("")), "/");
    EXPECT_EQ(errorWhere(bytes("not json")), "/");
    // What a file that is no glTF at all is called: empty, or not a glTF, rather than "malformed JSON".
    const auto reason = [](const std::string& s) {
        try {
            loadCharacterFromMemory(std::vector<std::uint8_t>(s.begin(), s.end()), "bad.glb");
        } catch (const GltfError& e) {
            return std::string(e.what());
        }
        return std::string("(loaded)");
    };
    EXPECT_NE(reason("").find("the file is empty (0 bytes)"), std::string::npos) << reason("");
    EXPECT_NE(reason("PK\x03\x04 a zip file").find("is not a glTF file"), std::string::npos) << reason("PK");
    EXPECT_NE(reason("{\"asset\": ").find("the JSON is malformed"), std::string::npos) << reason("{");
    EXPECT_EQ(errorWhere(bytes("[1, 2]")), "/");
    EXPECT_EQ(errorWhere(bytes(std::string(100000, '[') + std::string(100000, ']'))), "/");  // too deep: no stack overflow
    EXPECT_EQ(errorWhere(bytes(R"({"asset": {"version": "2.0"}})")), "/");  // nothing to load
    EXPECT_EQ(errorWhere(bytes(R"({"asset": {"version": "2.0"}, "nodes": {}})")), "/nodes");
    EXPECT_EQ(errorWhere(bytes(R"({"asset": {"version": "2.0"}, "skins": [{}]})")), "/skins/0");
    // GLB: truncated header, lying lengths.
    std::vector<std::uint8_t> glb = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 200, 0, 0, 0};
    EXPECT_EQ(errorWhere(glb), "/");
    glb = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 28, 0, 0, 0, 255, 255, 0, 0, 'J', 'S', 'O', 'N', '{', '}', ' ', ' ', ' ', ' ', ' ', ' '};
    EXPECT_EQ(errorWhere(glb), "/");
    glb[8] = 250;
    EXPECT_EQ(errorWhere(glb), "/");
    // External files: refused when not allowed, or when they leave the base directory.
    GltfTestFile f = twoJointRig();
    auto doc = J::parse(f.bytes());
    doc["buffers"][0]["uri"] = "../../etc/passwd";
    const std::string s = doc.dump();
    GltfLoadOptions o;
    o.baseDirectory = "/tmp";
    EXPECT_EQ(errorWhere(bytes(s), o), "/");
    o.allowExternalFiles = false;
    EXPECT_EQ(errorWhere(bytes(s), o), "/");
    // Limits.
    GltfLoadOptions small;
    small.limits.maxAccessorValues = 8;
    EXPECT_EQ(errorWhere(f.bytes(), small), "/accessors/4/count");  // the inverse bind matrices, read first
    small = {};
    small.limits.maxFileBytes = 100;
    EXPECT_EQ(errorWhere(f.bytes(), small), "/");
}

TEST(Gltf, AMinimalGlbLoads) {
    GltfTestFile f = twoJointRig();
    J doc = f.doc;
    doc["buffers"] = J::array({J{{"byteLength", f.bin.size()}}});
    std::string json = doc.dump();
    while (json.size() % 4) json += ' ';
    std::vector<std::uint8_t> bin = f.bin;
    while (bin.size() % 4) bin.push_back(0);
    auto u32 = [](std::vector<std::uint8_t>& v, std::uint32_t x) {
        for (int k = 0; k < 4; ++k) v.push_back(static_cast<std::uint8_t>(x >> (8 * k)));
    };
    std::vector<std::uint8_t> glb = {'g', 'l', 'T', 'F'};
    u32(glb, 2);
    u32(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    u32(glb, static_cast<std::uint32_t>(json.size()));
    u32(glb, 0x4E4F534A);
    glb.insert(glb.end(), json.begin(), json.end());
    u32(glb, static_cast<std::uint32_t>(bin.size()));
    u32(glb, 0x004E4942);
    glb.insert(glb.end(), bin.begin(), bin.end());
    const CharacterAsset a = loadCharacterFromMemory(glb, "rig.glb");
    EXPECT_EQ(a.characters[0].tmpl->name(), "rig");
    EXPECT_EQ(a.characters[0].jointCount, 2);
}
