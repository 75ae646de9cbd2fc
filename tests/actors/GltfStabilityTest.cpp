// The glTF loader on numerically awkward input: keys q and -q interpolate the short way, a looped
// clip sampled at t = 10^6 s gives the pose of its local time, weights that do not sum to one are
// normalised, more than eight influences keep the largest eight, and degenerate geometry loads.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/quaternion.hpp>

#include "throng/testkit/GltfTestFile.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/scenegraph/MeshDrawable.h"

using namespace throng;
using namespace throng::testkit;
using J = nlohmann::json;

namespace {

bool hasWarning(const CharacterAsset& a, const std::string& text) {
    for (const auto& w : a.warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

const MeshData& skinnedMesh(const CharacterAsset& a) {
    return dynamic_cast<const MeshDrawable&>(*a.characters[0].tmpl->rootGeometry().levels()[0].drawable).mesh();
}

glm::quat orientationAt(const ActorTemplate& t, double time, bool loop) {
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    t.clips()[0]->sample(t, time, loop, {}, dofs);
    const float* q = dofs.data() + t.dofValueOffset(1, 1);
    return glm::quat(q[3], q[0], q[1], q[2]);
}

}  // namespace

TEST(GltfStability, OppositeQuaternionKeysTakeTheShortPath) {
    // Key 1 is -q for q = 90 degrees about Y: the same rotation. Halfway must be 45 degrees, not 135.
    const float h = std::sqrt(0.5f);
    GltfTestFile f = twoJointRig();
    animate(f, 1, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, -h, 0, -h}, "VEC4");
    const auto t = loadCharacterFromMemory(f.bytes(), "q.gltf").characters[0].tmpl;
    const glm::quat q = orientationAt(*t, 0.5, false);
    const double angle = 2.0 * std::acos(std::min(1.0, std::abs(double(q.w))));
    EXPECT_NEAR(angle, M_PI / 4, 1e-5);
    EXPECT_NEAR(glm::length(q), 1.0, 1e-6);
}

TEST(GltfStability, LoopingAtAMillionSecondsGivesTheLocalTimePose) {
    GltfTestFile f = twoJointRig();
    const float s = std::sin(0.4f), c = std::cos(0.4f);
    animate(f, 1, "rotation", "LINEAR", {0, 0.35f, 0.7f}, {0, 0, 0, 1, 0, 0, s, c, 0, 0, 0, 1}, "VEC4");
    const auto t = loadCharacterFromMemory(f.bytes(), "loop.gltf").characters[0].tmpl;
    const double d = t->clips()[0]->duration();
    const double big = 1e6;
    const double local = std::fmod(big, d);
    const glm::quat a = orientationAt(*t, big, true), b = orientationAt(*t, local, false);
    for (int k = 0; k < 4; ++k) {
        EXPECT_TRUE(std::isfinite(a[k]));
        EXPECT_NEAR(a[k], b[k], 1e-6);
    }
    std::vector<float> dofs(t->restDofs().begin(), t->restDofs().end());
    t->clips()[0]->sample(*t, big, true, {}, dofs);
    std::vector<Affine> model(t->nodeCount());
    computeModelTransforms(*t, dofs, {}, model);
    for (const Affine& m : model)
        for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(m.translation[k]));
}

TEST(GltfStability, WeightsNotSummingToOneAreNormalisedWithAWarning) {
    GltfTestFile f = twoJointRig();
    f.doc["accessors"][2]["bufferView"] = f.view(std::vector<float>{0.5f, 0.5f, 0, 0, 2, 0, 0, 0, 0.3f, 0.1f, 0, 0, 1, 0, 0, 0}.data(), 64);
    const CharacterAsset a = loadCharacterFromMemory(f.bytes(), "w.gltf");
    EXPECT_TRUE(hasWarning(a, "not summing to 1"));
    const MeshData& m = skinnedMesh(a);
    for (std::size_t v = 0; v < m.vertexCount(); ++v)
        EXPECT_NEAR(m.weights0[v].x + m.weights0[v].y + m.weights0[v].z + m.weights0[v].w, 1.0f, 1e-6f) << v;
    EXPECT_NEAR(m.weights0[2].x, 0.75f, 1e-6f);
    EXPECT_EQ(m.joints0[1].x, 0);  // vertex 1: joint 0 with weight 2 -> 1
}

TEST(GltfStability, SmallWeightErrorsAreLeftAlone) {
    GltfTestFile f = twoJointRig();
    f.doc["accessors"][2]["bufferView"] = f.view(std::vector<float>{0.999f, 0, 0, 0, 1, 0, 0, 0, 0.75f, 0.25f, 0, 0, 1, 0, 0, 0}.data(), 64);
    EXPECT_FALSE(hasWarning(loadCharacterFromMemory(f.bytes(), "w.gltf"), "not summing to 1"));
}

TEST(GltfStability, MoreThanEightInfluencesKeepTheLargestEight) {
    // 12 joints in a chain; vertex 0 has 12 influences in three sets (weights 1..12 / 78).
    GltfTestFile f;
    std::vector<int> joints;
    for (int j = 0; j < 12; ++j) {
        J node = {{"name", "j" + std::to_string(j)}, {"translation", {0, 0.1, 0}}};
        if (j < 11) node["children"] = J::array({j + 1});
        joints.push_back(f.push("nodes", node));
    }
    const int pos = f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    J attributes = {{"POSITION", pos}};
    for (int set = 0; set < 3; ++set) {
        std::vector<std::uint16_t> jv(12, 0);
        std::vector<float> wv(12, 0.0f);
        for (int k = 0; k < 4; ++k) {
            jv[static_cast<std::size_t>(k)] = static_cast<std::uint16_t>(set * 4 + k);
            wv[static_cast<std::size_t>(k)] = float(set * 4 + k + 1) / 78.0f;
        }
        for (int v = 1; v < 3; ++v) jv[static_cast<std::size_t>(v * 4)] = 0, wv[static_cast<std::size_t>(v * 4)] = set == 0 ? 1.0f : 0.0f;
        attributes["JOINTS_" + std::to_string(set)] = f.u16(jv, "VEC4", 4);
        attributes["WEIGHTS_" + std::to_string(set)] = f.floats(wv, "VEC4");
    }
    f.push("meshes", {{"primitives", J::array({J{{"attributes", attributes}}})}});
    const int body = f.push("nodes", {{"mesh", 0}, {"skin", 0}});
    f.push("skins", {{"joints", joints}});
    f.push("scenes", {{"nodes", J::array({0, body})}});
    const CharacterAsset a = loadCharacterFromMemory(f.bytes(), "eight.gltf");
    EXPECT_TRUE(hasWarning(a, "more than 8 influences"));
    const MeshData& m = skinnedMesh(a);
    EXPECT_EQ(m.influenceCount(), 8);
    // Kept: joints 11..4 (weights 12..5), renormalised by their sum 68.
    EXPECT_EQ(m.joints0[0].x, 11);
    EXPECT_NEAR(m.weights0[0].x, 12.0f / 68.0f, 1e-6f);
    EXPECT_EQ(m.joints1[0].w, 4);
    EXPECT_NEAR(m.weights1[0].w, 5.0f / 68.0f, 1e-6f);
    float sum = 0;
    for (int k = 0; k < 4; ++k) sum += m.weights0[0][k] + m.weights1[0][k];
    EXPECT_NEAR(sum, 1.0f, 1e-6f);
}

TEST(GltfStability, AllZeroWeightsBindToTheFirstJoint) {
    GltfTestFile f = twoJointRig();
    f.doc["accessors"][2]["bufferView"] = f.view(std::vector<float>(16, 0.0f).data(), 64);
    const CharacterAsset a = loadCharacterFromMemory(f.bytes(), "z.gltf");
    EXPECT_TRUE(hasWarning(a, "no weight"));
    const MeshData& m = skinnedMesh(a);
    for (std::size_t v = 0; v < m.vertexCount(); ++v) {
        EXPECT_EQ(m.joints0[v].x, 0);
        EXPECT_FLOAT_EQ(m.weights0[v].x, 1.0f);
    }
}

TEST(GltfStability, DegenerateCasesLoad) {
    // Zero-area triangles, a single-key clip, a joint no vertex follows, repeated names, a joint
    // scaled to zero: all load, and the template's spheres stay finite.
    GltfTestFile f = twoJointRig();
    f.doc["accessors"][0]["bufferView"] = f.view(std::vector<float>(12, 0.25f).data(), 48);
    f.doc["nodes"][1]["name"] = "hip";
    f.doc["nodes"][1]["scale"] = {0, 0, 0};
    animate(f, 1, "translation", "LINEAR", {0.5f}, {1, 2, 3}, "VEC3");
    const CharacterAsset a = loadCharacterFromMemory(f.bytes(), "degenerate.gltf");
    const ActorTemplate& t = *a.characters[0].tmpl;
    EXPECT_NE(t.nodes()[0].name, t.nodes()[1].name);
    EXPECT_TRUE(std::isfinite(t.skeletonRootRadius()));
    EXPECT_DOUBLE_EQ(t.clips()[0]->duration(), 0.5);
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    t.clips()[0]->sample(t, 123.4, true, {}, dofs);
    EXPECT_FLOAT_EQ(dofs[t.dofValueOffset(1, 0)], 1.0f);
}
