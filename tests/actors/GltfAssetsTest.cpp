// The glTF loader on the third-party assets beside the project (../shared/assets): joint and clip
// counts of the characters, the two minimal rigs sampled against values computed by hand from
// their files, every malformed file giving its expected result, and joint spheres staying inside
// the Sklsroot sphere over every clip.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "throng/testkit/Assets.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/scenegraph/MeshDrawable.h"

using namespace throng;

namespace {

std::string asset(const std::string& path) { return testkit::sharedAssets() + "/" + path; }

std::vector<std::string> clipNames(const ActorTemplate& t) {
    std::vector<std::string> names;
    for (const auto& c : t.clips()) names.push_back(c->name());
    return names;
}

std::vector<Affine> modelAt(const ActorTemplate& t, std::size_t clip, double time) {
    std::vector<float> dofs(t.restDofs().begin(), t.restDofs().end());
    if (clip < t.clips().size()) t.clips()[clip]->sample(t, time, false, {}, dofs);
    std::vector<Affine> model(t.nodeCount());
    computeModelTransforms(t, dofs, {}, model);
    return model;
}

}  // namespace

TEST(GltfAssets, CharactersHaveTheirJointsAndClips) {
    const CharacterAsset cesium = loadCharacter(asset("characters/CesiumMan.glb"));
    ASSERT_TRUE(cesium.primaryTemplate());
    EXPECT_EQ(cesium.characters[0].jointCount, 19);
    EXPECT_EQ(cesium.primaryTemplate()->clips().size(), 1u);
    const auto& mesh = dynamic_cast<const MeshDrawable&>(*cesium.primaryTemplate()->rootGeometry().levels()[0].drawable).mesh();
    ASSERT_TRUE(mesh.baseColorTexture);  // the JPEG texture, decoded by libjpeg-turbo
    EXPECT_TRUE(mesh.baseColorTexture->valid());

    const CharacterAsset fox = loadCharacter(asset("characters/Fox.glb"));
    EXPECT_EQ(fox.characters[0].jointCount, 24);
    EXPECT_EQ(clipNames(*fox.primaryTemplate()), (std::vector<std::string>{"Survey", "Walk", "Run"}));
    EXPECT_GT(fox.primaryTemplate()->skeletonRootMargin(), 0.05);  // centimetres: 1% of its size

    const CharacterAsset robot = loadCharacter(asset("characters/robot.glb"));
    EXPECT_EQ(robot.characters[0].jointCount, 43);
    EXPECT_EQ(robot.primaryTemplate()->clips().size(), 14u);
    for (const auto* a : {&cesium, &fox, &robot}) {
        EXPECT_TRUE(a->warnings.size() <= 1) << a->source;
        for (const LoadedAnimation& an : a->animations) EXPECT_EQ(an.channels, an.channelsLoaded) << an.name;
    }
}

TEST(GltfAssets, SimpleSkinMatchesHandComputedValues) {
    // Joint 1 (node 2) turns about Z: keys every 0.5 s; at 1.0 s it is (0, 0, 0.707, 0.707), 90 degrees.
    const CharacterAsset a = loadCharacter(asset("minimal/SimpleSkin.gltf"));
    const ActorTemplate& t = *a.primaryTemplate();
    ASSERT_EQ(t.nodeCount(), 2u);
    auto model = modelAt(t, 0, 1.0);
    const Mat4 m1 = model[1].toDMat4();
    EXPECT_NEAR(m1[3][1], 1.0, 1e-6);           // at (0, 1, 0)
    EXPECT_NEAR(m1[0][0], 0.0, 1e-3);           // x axis turned onto y
    EXPECT_NEAR(m1[0][1], 1.0, 1e-3);
    // Vertex (1, 2, 0), bound to joint 1 alone: IBM translates by (-0.5, -1, 0), so it lands at
    // (0, 1, 0) + R90z (0.5, 1, 0) = (-1, 1.5, 0).
    std::vector<glm::mat4> palette(2);
    computeSkinPalette(t, t.skins()[0], model, {}, palette);
    const glm::vec4 p = palette[1] * glm::vec4(1, 2, 0, 1);
    EXPECT_NEAR(p.x, -1.0f, 2e-3f);
    EXPECT_NEAR(p.y, 1.5f, 2e-3f);
    // At 0.25 s, halfway between 0 and 45 degrees: 22.5 degrees.
    model = modelAt(t, 0, 0.25);
    EXPECT_NEAR(std::atan2(model[1].toDMat4()[0][1], model[1].toDMat4()[0][0]), M_PI / 8, 2e-3);
}

TEST(GltfAssets, RiggedSimpleFoldsItsZUpArmatureAndMatchesTheFile) {
    const CharacterAsset a = loadCharacter(asset("minimal/RiggedSimple.glb"));
    const ActorTemplate& t = *a.primaryTemplate();
    ASSERT_EQ(t.nodeCount(), 2u);  // Z_UP and Armature folded into Bone
    // World matrix of Bone from the file: Z_UP * Armature * Bone (column-major matrices).
    const double zup[16] = {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1};
    const double arm[16] = {-4.3711398944878965e-08, -1, 0, 0, 1, -4.3711398944878965e-08, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const double bone[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1.3597299641787686e-07, -4.1803297996521, 1};
    const Mat4 world = glm::make_mat4(zup) * glm::make_mat4(arm) * glm::make_mat4(bone);
    const auto rest = modelAt(t, 99, 0);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(rest[0].toDMat4()[c][r], world[c][r], 1e-5);
    // Key 1 (t = 0.0833 s) of Bone.001: translation (-4.58e-14, 0.0279775, 4.187077), rotation
    // (0.0123278, 0.00028990, -3.5741e-06, -0.999924), scale 1.
    const double t1 = 0.08333330601453781;
    const auto model = modelAt(t, 0, t1);
    const glm::dquat q = glm::normalize(glm::dquat(-0.9999240040779114, 0.012327802367508411, 0.00028990054852329195, -3.5741229567065602e-06));
    const Mat4 local = glm::translate(Mat4(1), Vec3(-4.5771498841541e-14, 0.027977488934993744, 4.187077045440674)) * glm::mat4_cast(q);
    const Mat4 expected = model[0].toDMat4() * local;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(model[1].toDMat4()[c][r], expected[c][r], 1e-5);
}

TEST(GltfAssets, MalformedFilesGiveTheirExpectedResults) {
    struct Case {
        const char* file;
        const char* where;    // error pointer, or "" when it loads
        const char* warning;  // text of a warning it must give when it loads
    };
    const Case cases[] = {
        {"skin/buffer_view_bytestride.gltf", "/buffers/0", ""},
        {"skin/custom_property.gltf", "", "no mesh uses the skin"},
        {"skin/empty_array.gltf", "/", ""},
        {"skin/empty_joints_array.gltf", "/skins/0/joints", ""},
        {"skin/empty_object.gltf", "/skins/0", ""},
        {"skin/ibm_invalid_count.gltf", "/skins/2/inverseBindMatrices", ""},
        {"skin/ibm_invalid_format.gltf", "/skins/0/inverseBindMatrices", ""},
        {"skin/ignored_animated_transform.gltf", "", "not a joint"},
        {"skin/ignored_local_transform.gltf", "", "local transform of a skinned mesh node is ignored"},
        {"skin/ignored_parent_transform.gltf", "", "parent nodes are ignored"},
        {"skin/no_common_root.gltf", "/skins/0/joints", ""},
        {"skin/no_joints_in_scene.gltf", "/nodes/2", ""},
        {"skin/skeleton_invalid.gltf", "/skins/0/skeleton", ""},
        {"skin/unresolved_ibm.gltf", "/skins/0/inverseBindMatrices", ""},
        {"skin/unresolved_joint.gltf", "/skins/0/joints/0", ""},
        {"skin/unresolved_skeleton.gltf", "/skins/0/skeleton", ""},
        {"skin/valid.gltf", "", ""},
        {"skin_data/invalid_ibm.gltf", "/skins/0/inverseBindMatrices", ""},
    };
    for (const Case& c : cases) {
        const std::string path = asset(std::string("malformed/gltf-validator/") + c.file);
        try {
            const CharacterAsset a = loadCharacter(path);
            EXPECT_STREQ(c.where, "") << c.file << " loaded";
            bool found = std::string(c.warning).empty();
            for (const auto& w : a.warnings) found = found || w.find(c.warning) != std::string::npos;
            EXPECT_TRUE(found) << c.file << ": no warning '" << c.warning << "'";
        } catch (const GltfError& e) {
            EXPECT_EQ(e.where(), c.where) << c.file << ": " << e.what();
            if (std::string(c.file) == "skin_data/invalid_ibm.gltf") {
                EXPECT_NE(e.problem().find("not affine"), std::string::npos);
            }
        }
    }
    const CharacterAsset fox = loadCharacter(asset("malformed/Fox_2022_bevy_invalid/Fox.glb"));
    EXPECT_EQ(fox.characters[0].jointCount, 24);
    EXPECT_EQ(fox.primaryTemplate()->clips().size(), 3u);
    bool stride = false;
    for (const auto& w : fox.warnings) stride = stride || w.find("byteStride") != std::string::npos;
    EXPECT_TRUE(stride);
}

TEST(GltfAssets, KenneyTilesAreWorldSpaceWithOneSharedTexture) {
    const CharacterAsset a = loadCharacter(asset("town/kenney_city_builder/building-small-a.glb"));
    ASSERT_FALSE(a.primitives.empty());
    const Image* shared = a.primitives[0].data->baseColorTexture.get();
    ASSERT_NE(shared, nullptr);
    EXPECT_TRUE(shared->valid());
    for (const LoadedPrimitive& p : a.primitives) {
        EXPECT_EQ(p.skin, -1);
        EXPECT_NO_THROW(MeshDrawable{p.data});
        if (p.data->baseColorTexture) {
            EXPECT_EQ(p.data->baseColorTexture.get(), shared);
        }
    }
    EXPECT_EQ(a.characters.size(), 1u);
    EXPECT_EQ(a.characters[0].tmpl->name(), "building-small-a");
}

TEST(GltfAssets, JointSpheresStayInsideTheSklsrootSphereOverEveryClip) {
    for (const char* file : {"characters/CesiumMan.glb", "characters/Fox.glb", "characters/robot.glb",
                             "minimal/RiggedSimple.glb", "minimal/SimpleSkin.gltf"}) {
        const auto t = loadCharacter(asset(file)).primaryTemplate();
        const BoundingSphere root(Vec3(0), t->skeletonRootRadius());
        std::vector<BoundingSphere> geometry(t->nodeCount()), subtree(t->nodeCount());
        for (std::size_t c = 0; c < t->clips().size(); ++c) {
            const double d = t->clips()[c]->duration();
            for (double time = 0; time <= d; time += 1.0 / 97.0) {  // off the loader's sampling grid
                const auto model = modelAt(*t, c, time);
                computeInternalSpheres(*t, model, {}, geometry, subtree);
                for (std::size_t i = 0; i < t->nodeCount(); ++i)
                    ASSERT_TRUE(root.contains(geometry[i])) << file << " clip " << t->clips()[c]->name() << " t " << time
                                                            << " node " << t->nodes()[i].name;
            }
        }
    }
}

TEST(GltfAssets, RobotExpressiveLoadsItsFaceTargetsAndTheirClips) {
    const CharacterAsset a = loadCharacter(testkit::characterPath("RobotExpressive.glb"));
    const ActorTemplate& t = *a.primaryTemplate();
    for (const char* name : {"Angry", "Surprised", "Sad"}) EXPECT_GE(t.findMorphChannel(name), 0) << name;
    EXPECT_EQ(t.morphChannels().size(), 3u);
    std::size_t weightChannels = 0;
    for (const auto& clip : t.clips())
        for (const ClipChannel& c : clip->channels()) weightChannels += c.target == ClipChannel::Target::MorphWeight;
    EXPECT_GE(weightChannels, t.clips().size());  // every clip drives the face
    for (const std::string& w : a.warnings) EXPECT_EQ(w.find("morph target"), std::string::npos) << w;
}
