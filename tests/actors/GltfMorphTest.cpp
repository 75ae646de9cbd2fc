// glTF morph targets: offsets read per primitive (POSITION, NORMAL; TANGENT checked and dropped),
// names from extras.targetNames, default weights from mesh.weights, weights animation channels as
// clip channels of the template's morph channels (every interpolation), carried into the frame of
// a rigid part or merged into the skinned mesh; every malformed case an error naming its accessor.

#include <gtest/gtest.h>

#include <cmath>

#include "throng/actors/SkeletonPose.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/testkit/GltfTestFile.h"

using namespace throng;
using namespace throng::testkit;
using J = nlohmann::json;

namespace {

CharacterAsset load(const GltfTestFile& f) { return loadCharacterFromMemory(f.bytes(), "test.gltf"); }

// The JSON pointer and message of the error loading `f`, or "(loaded)".
std::string errorOf(const GltfTestFile& f) {
    try {
        load(f);
    } catch (const GltfError& e) {
        return e.where() + ": " + e.what();
    }
    return "(loaded)";
}

bool hasWarning(const CharacterAsset& a, const std::string& text) {
    for (const auto& w : a.warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

// The two-joint rig with two morph targets on its quad: "smile" lifts every vertex by 0.1 in y,
// "frown" moves vertex 2 by -0.2 in x; default weights 0.25 and 0.
GltfTestFile morphRig() {
    GltfTestFile f = twoJointRig();
    const int smile = f.floats({0, 0.1f, 0, 0, 0.1f, 0, 0, 0.1f, 0, 0, 0.1f, 0}, "VEC3");
    const int frown = f.floats({0, 0, 0, 0, 0, 0, -0.2f, 0, 0, 0, 0, 0}, "VEC3");
    f.doc["meshes"][0]["primitives"][0]["targets"] = J::array({{{"POSITION", smile}}, {{"POSITION", frown}}});
    f.doc["meshes"][0]["weights"] = {0.25, 0.0};
    f.doc["meshes"][0]["extras"] = {{"targetNames", {"smile", "frown"}}};
    return f;
}

// Animates the weights of node 2 (the rig's mesh) with `values` (two per key, or six for CUBICSPLINE).
void animateWeights(GltfTestFile& f, const char* interpolation, const std::vector<float>& times, const std::vector<float>& values) {
    animate(f, 2, "weights", interpolation, times, values, "SCALAR");
}

// The template's weight of morph channel `name` in `dofs`.
float weightOf(const ActorTemplate& t, std::span<const float> dofs, const char* name) {
    const int c = t.findMorphChannel(name);
    EXPECT_GE(c, 0) << name;
    return c < 0 ? NAN : dofs[t.morphWeightOffset() + static_cast<std::size_t>(c)];
}

}  // namespace

TEST(GltfMorph, TargetsLoadWithTheirNamesDefaultWeightsAndOffsets) {
    const CharacterAsset a = load(morphRig());
    ASSERT_EQ(a.primitives.size(), 1u);
    const MeshData& m = *a.primitives[0].data;
    ASSERT_EQ(m.morphTargets.size(), 2u);
    EXPECT_EQ(m.morphTargets[0].name, "smile");
    EXPECT_EQ(m.morphTargets[1].name, "frown");
    EXPECT_FLOAT_EQ(m.morphTargets[0].defaultWeight, 0.25f);
    EXPECT_FLOAT_EQ(m.morphTargets[0].positions[3].y, 0.1f);
    EXPECT_FLOAT_EQ(m.morphTargets[1].positions[2].x, -0.2f);
    const ActorTemplate& t = *a.characters[0].tmpl;
    ASSERT_EQ(t.morphChannels().size(), 2u);
    EXPECT_EQ(t.morphChannels()[0], "smile");
    EXPECT_EQ(t.dofValueCount(), t.morphWeightOffset() + 2);
    EXPECT_FLOAT_EQ(weightOf(t, t.restDofs(), "smile"), 0.25f);
    EXPECT_FLOAT_EQ(weightOf(t, t.restDofs(), "frown"), 0.0f);
    // The skinned mesh (the actor's vaLod) keeps them, mapped to the channels.
    const auto map = t.morphChannelsOf(t.nodeCount(), 0);
    EXPECT_EQ(std::vector<std::uint32_t>(map.begin(), map.end()), (std::vector<std::uint32_t>{0, 1}));
    // Bounds hold every shape weights up to 1 make: the quad reaches 1.5 + 0.1 in y.
    const BoundingSphere b = m.computeBound();
    EXPECT_GE(b.center().y + b.radius(), 1.6 - 1e-6);
}

TEST(GltfMorph, UnnamedTargetsAreNumberedAndRepeatedNamesMadeUnique) {
    GltfTestFile f = morphRig();
    f.doc["meshes"][0].erase("extras");
    EXPECT_EQ(load(f).primitives[0].data->morphTargets[1].name, "target1");
    f.doc["meshes"][0]["extras"] = {{"targetNames", {"same", "same"}}};
    const CharacterAsset a = load(f);
    EXPECT_EQ(a.primitives[0].data->morphTargets[1].name, "same#2");
    EXPECT_TRUE(hasWarning(a, "repeats 'same'"));
    f.doc["meshes"][0]["extras"] = {{"targetNames", {"only one"}}};
    const CharacterAsset b = load(f);
    EXPECT_EQ(b.primitives[0].data->morphTargets[0].name, "target0");
    EXPECT_TRUE(hasWarning(b, "targets named by number"));
}

TEST(GltfMorph, NormalOffsetsLoadAndTangentOffsetsAreCheckedThenDropped) {
    GltfTestFile f = morphRig();
    const int normals = f.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    f.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = normals;
    const int dn = f.floats({0.5f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3");
    const int dt = f.floats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3");
    f.doc["meshes"][0]["primitives"][0]["targets"][0]["NORMAL"] = dn;
    f.doc["meshes"][0]["primitives"][0]["targets"][1]["TANGENT"] = dt;
    const CharacterAsset a = load(f);
    const MeshData& m = *a.primitives[0].data;
    ASSERT_EQ(m.morphTargets[0].normals.size(), 4u);
    EXPECT_FLOAT_EQ(m.morphTargets[0].normals[0].x, 0.5f);
    EXPECT_TRUE(m.morphTargets[1].normals.empty());
    EXPECT_TRUE(hasWarning(a, "offsets of TANGENT are not used"));
    // A TANGENT target is still checked: one of the wrong size is an error.
    const int shortTangent = f.floats({0, 0, 0}, "VEC3");
    f.doc["meshes"][0]["primitives"][0]["targets"][1]["TANGENT"] = shortTangent;
    EXPECT_EQ(errorOf(f).substr(0, 40), "/meshes/0/primitives/0/targets/1/TANGENT");
}

TEST(GltfMorph, EveryMalformedTargetIsAnErrorNamingItsAccessor) {
    {  // a target whose count differs from its primitive's
        GltfTestFile f = morphRig();
        f.doc["meshes"][0]["primitives"][0]["targets"][1]["POSITION"] = f.floats({0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3");
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/meshes/0/primitives/0/targets/1/POSITION") << e;
        EXPECT_NE(e.find("holds 3 offsets, the primitive has 4 vertices"), std::string::npos) << e;
    }
    {  // a target of the wrong type
        GltfTestFile f = morphRig();
        f.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = f.floats({0, 0, 0, 0, 0, 0, 0, 0}, "VEC2");
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/meshes/0/primitives/0/targets/0/POSITION") << e;
    }
    {  // NaN in a target
        GltfTestFile f = morphRig();
        const int nan = f.floats({0, NAN, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3");
        f.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = nan;
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/accessors/" + std::to_string(nan)) << e;
        EXPECT_NE(e.find("value 1 is not finite"), std::string::npos) << e;
    }
    {  // default weights that do not match the targets
        GltfTestFile f = morphRig();
        f.doc["meshes"][0]["weights"] = {0.5};
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/meshes/0/weights") << e;
    }
    {  // primitives of one mesh with different numbers of targets
        GltfTestFile f = morphRig();
        J second = f.doc["meshes"][0]["primitives"][0];
        second["targets"] = J::array({second["targets"][0]});
        f.doc["meshes"][0]["primitives"].push_back(second);
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/meshes/0/primitives/1/targets") << e;
    }
}

TEST(GltfMorph, EveryMalformedWeightsChannelIsAnErrorNamingItsAccessor) {
    {  // output not a multiple of the target count
        GltfTestFile f = morphRig();
        animateWeights(f, "LINEAR", {0, 1}, {0, 1, 0});
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/animations/0/samplers/0/output") << e;
        EXPECT_NE(e.find("not a multiple of the 2 morph targets"), std::string::npos) << e;
    }
    {  // a multiple, but not one per key
        GltfTestFile f = morphRig();
        animateWeights(f, "LINEAR", {0, 1}, {0, 1, 0, 1, 0, 1});
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/animations/0/samplers/0/output") << e;
    }
    {  // CUBICSPLINE needs three per key per target
        GltfTestFile f = morphRig();
        animateWeights(f, "CUBICSPLINE", {0, 1}, {0, 1, 0, 1});
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/animations/0/samplers/0/output") << e;
    }
    {  // NaN weight
        GltfTestFile f = morphRig();
        animateWeights(f, "LINEAR", {0, 1}, {0, 1, NAN, 1});
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/accessors/" + std::to_string(f.doc["animations"][0]["samplers"][0]["output"].get<int>())) << e;
        EXPECT_NE(e.find("value 2 is not finite"), std::string::npos) << e;
    }
    {  // the weights of a node whose mesh has no target
        GltfTestFile f = twoJointRig();
        animate(f, 2, "weights", "LINEAR", {0, 1}, {0, 1}, "SCALAR");
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/animations/0/channels/0/target") << e;
    }
    {  // weights as VEC3
        GltfTestFile f = morphRig();
        animate(f, 2, "weights", "LINEAR", {0, 1}, {0, 1, 0, 1, 0, 1}, "VEC3");
        const std::string e = errorOf(f);
        EXPECT_EQ(e.substr(0, e.find(':')), "/animations/0/samplers/0/output") << e;
    }
}

TEST(GltfMorph, WeightsChannelsSampleWithEveryInterpolation) {
    for (const char* interpolation : {"LINEAR", "STEP"}) {
        GltfTestFile f = morphRig();
        animateWeights(f, interpolation, {0, 1}, {0.0f, 1.0f, 1.0f, 0.5f});  // key 0: smile 0, frown 1; key 1: 1, 0.5
        const CharacterAsset a = load(f);
        const ActorTemplate& t = *a.characters[0].tmpl;
        ASSERT_EQ(t.clips().size(), 1u) << interpolation;
        const AnimationClip& clip = *t.clips()[0];
        ASSERT_EQ(clip.channels().size(), 2u);
        EXPECT_EQ(clip.channels()[0].target, ClipChannel::Target::MorphWeight);
        std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
        clip.sample(t, 0.25, false, {}, dofs);
        const bool linear = std::string(interpolation) == "LINEAR";
        EXPECT_NEAR(weightOf(t, dofs, "smile"), linear ? 0.25f : 0.0f, 1e-6) << interpolation;
        EXPECT_NEAR(weightOf(t, dofs, "frown"), linear ? 0.875f : 1.0f, 1e-6) << interpolation;
        EXPECT_EQ(a.animations[0].channelsLoaded, 1);
    }
    // CUBICSPLINE: per key the in-tangents of both targets, their values, their out-tangents.
    GltfTestFile f = morphRig();
    animateWeights(f, "CUBICSPLINE", {0, 1}, {0, 0, 0, 1, 1, 0, /* key 1 */ 0, 0, 1, 0, 0, 0});
    const CharacterAsset a = load(f);
    const ActorTemplate& t = *a.characters[0].tmpl;
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    t.clips()[0]->sample(t, 0.5, false, {}, dofs);
    // smile: p0 = 0, m0 = 1, p1 = 1, m1 = 0 at u = 0.5: h10 = 0.125, h01 = 0.5: 0.625.
    EXPECT_NEAR(weightOf(t, dofs, "smile"), 0.625f, 1e-6);
    // frown: p0 = 1, m0 = 0, p1 = 0, m1 = 0: h00 = 0.5.
    EXPECT_NEAR(weightOf(t, dofs, "frown"), 0.5f, 1e-6);
}

TEST(GltfMorph, RigidPartsCarryTheirOffsetsIntoTheJointFrame) {
    // A rigid mesh under the knee, its node turned 90 degrees about z: a target offset along the
    // mesh's x is along the knee's y.
    GltfTestFile f = twoJointRig();
    const int pos = f.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int off = f.floats({1, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3");
    J prim = {{"attributes", {{"POSITION", pos}}}, {"targets", J::array({{{"POSITION", off}}})}};
    f.push("meshes", {{"primitives", J::array({prim})}, {"extras", {{"targetNames", {"open"}}}}});
    const double h = std::sqrt(0.5);
    const int node = f.push("nodes", {{"name", "jaw"}, {"mesh", 1}, {"rotation", {0, 0, h, h}}});
    f.doc["nodes"][1]["children"] = J::array({node});
    const CharacterAsset a = load(f);
    const ActorTemplate& t = *a.characters[0].tmpl;
    ASSERT_EQ(t.morphChannels().size(), 1u);
    EXPECT_EQ(t.morphChannels()[0], "open");
    bool found = false;
    for (std::size_t i = 0; i < t.nodeCount(); ++i) {
        const auto map = t.morphChannelsOf(i, 0);
        if (map.empty()) continue;
        found = true;
        const auto& mesh = static_cast<const MeshDrawable&>(*t.nodes()[i].geometry.levels()[0].drawable).mesh();
        EXPECT_NEAR(mesh.morphTargets[0].positions[0].x, 0.0f, 1e-6);
        EXPECT_NEAR(mesh.morphTargets[0].positions[0].y, 1.0f, 1e-6);
    }
    EXPECT_TRUE(found);
}

TEST(GltfMorph, SkinnedPrimitivesMergeTheirTargetsByName) {
    GltfTestFile f = morphRig();
    J second = f.doc["meshes"][0]["primitives"][0];
    // Same targets count, other names order is the mesh's: both primitives of one mesh share names.
    f.doc["meshes"][0]["primitives"].push_back(second);
    const CharacterAsset a = load(f);
    const ActorTemplate& t = *a.characters[0].tmpl;
    const auto& mesh = static_cast<const MeshDrawable&>(*t.rootGeometry().levels()[0].drawable).mesh();
    ASSERT_EQ(mesh.vertexCount(), 8u);
    ASSERT_EQ(mesh.morphTargets.size(), 2u);
    EXPECT_EQ(mesh.morphTargets[1].positions.size(), 8u);
    EXPECT_FLOAT_EQ(mesh.morphTargets[1].positions[6].x, -0.2f);  // vertex 2 of the second primitive
}
