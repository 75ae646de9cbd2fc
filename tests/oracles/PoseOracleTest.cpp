// Poses checked against another implementation: CesiumMan, Fox and the robot loaded by Throng's glTF
// loader and played by KeyframeBehaviour / ActorProcessor (CPU-skinned with each draw item's
// palette), against the same files read, animated and skinned by VTK 9.1's vtkGLTFReader.
//
// Frame: the world frame of an actor standing at the origin facing +Z (testkit::Stage), which is the
// glTF default scene's frame scaled by GltfLoadOptions::scale. Each file is loaded with the scale
// the town gives it (apps/town/scenes/default.json: CesiumMan 1, robot 0.32, Fox 0.01, Fox being
// modelled in centimetres), VTK's points (file units) are multiplied by the same scale, so errors are
// millimetres on a character of real size. Throng folds the non-joint nodes above the skeleton
// (CesiumMan's Z_UP and Armature matrices, Fox's root, the robot's RobotArmature) into its Skeleton
// nodes; VTK keeps them as nodes and skins with inverse(mesh node global) * joint global * inverse
// bind, then applies the mesh node's global transform, which cancels: both give the glTF skinning
// formula, sum_k w_k * globalJoint_k * inverseBind_k * v, in the scene frame.
//
// Matching: VTK's blocks are the default scene's nodes depth first, children in order, primitives in
// order; Throng merges a skin's primitives in that same order without reordering vertices. The test
// asserts that the vertex counts of every primitive agree, then compares vertex i with vertex i.
//
// Times: start, 1/8 ... 7/8 of the clip and 0.37, 0.63 (off the eighths), the end, and past the
// end. glTF defines no runtime behaviour such as looping ("this specification doesn't define any
// runtime behavior, such as: order of playing, auto-start, loops"), only that a sampler's output
// is clamped before and after its input range. Throng's KeyframeBehaviour loops (the clip time
// wraps into [0, duration)); VTK does not (past the last key it holds it). So at t = duration
// Throng's actor shows the start of the clip again, compared with VTK at 0; the end itself is
// compared through Throng's pose kernels sampled without looping (clamped, as the specification
// says); 1.37 x duration is compared with VTK at 0.37 x duration. The rest pose (no animation) is
// compared too.
//
// Disagreements: none on these files; Throng and VTK agree within rounding at every sample. The
// parts of the specification the three files do not exercise (CUBICSPLINE, STEP, quaternions of
// opposite signs, animated nodes above the skeleton) are checked in SpecRigOracleTest.
//
// Tolerance 0.01 mm: both sides compute in single precision (Throng's palettes and skinMesh; VTK's
// keys, quaternions and points are floats, its matrices doubles), so what remains is rounding.
// Measured worst (CesiumMan, Fox, robot): 0.0005, 0.0005, 0.0009 mm.
//
// Negative control: one joint's palette entry turned by 1 degree about its own origin must put the
// comparison out of tolerance (measured: 3.8 to 8.9 mm).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <numbers>
#include <sstream>

#include "throng/testkit/Cameras.h"
#include "throng/testkit/CharacterStage.h"
#include "ThrongPoses.h"
#include "VtkGltfPoser.h"
#include "throng/actors/AnimationClip.h"
#include "throng/actors/SkeletonPose.h"

namespace throng {
namespace {

// Largest distance allowed between a Throng vertex and the VTK vertex, millimetres on the character
// at real size (see above).
constexpr double kToleranceMm = 0.01;

struct OracleCharacter {
    const char* file;
    double scale;                    // GltfLoadOptions::scale (the town's)
    std::vector<std::string> clips;  // Throng clip names ("" for the first clip)
};

const OracleCharacter kCharacters[] = {
    {"CesiumMan.glb", 1.0, {""}},  // the file has one animation
    {"Fox.glb", 0.01, {"Survey", "Walk", "Run"}},
    {"robot.glb", 0.32, {"Robot_Walking", "Robot_Running", "Robot_Idle", "Robot_Dance"}},
};

// gtest names a failing case by its file.
void PrintTo(const OracleCharacter& c, std::ostream* os) { *os << c.file; }

// How Throng is asked for a pose, and which VTK time it is compared with.
struct Sample {
    double throngTime;  // seconds
    bool looped;        // through the actor (KeyframeBehaviour loops) or the kernels with a clamped clip
    double vtkTime;     // seconds
    std::string label;
};

std::vector<Sample> samplesOf(double d) {
    std::vector<Sample> s;
    for (double f : {0.0, 0.125, 0.25, 0.37, 0.5, 0.63, 0.75, 0.875}) {
        std::ostringstream l;
        l << f << " d";
        s.push_back({f * d, true, f * d, l.str()});
    }
    s.push_back({d, false, d, "end (clamped)"});
    s.push_back({d, true, 0.0, "end (looped: wraps to 0)"});
    s.push_back({1.37 * d, true, 0.37 * d, "1.37 d (looped: 0.37 d)"});
    return s;
}

// A camera from which the whole actor is drawn (the processor culls nothing).
Camera farCamera(double r) {
    return testkit::lookingAt(Vec3(0.0, 0.0, 50.0 * r), Vec3(0.0), {std::numbers::pi / 4.0, 1.0, 0.01 * r, 200.0 * r});
}

// The palette of the template's skin for clip `clip` at `t`, sampled by the pose kernels without
// looping; at rest (the nodes' own transforms in the file) when `clip` is -1.
std::vector<glm::mat4> clampedPalette(const ActorTemplate& tmpl, int clip, double t) {
    std::vector<float> dofs(tmpl.restDofs().begin(), tmpl.restDofs().end());
    if (clip >= 0) tmpl.clips()[std::size_t(clip)]->sample(tmpl, t, false, {}, dofs);
    std::vector<Affine> model(tmpl.nodeCount());
    computeModelTransforms(tmpl, dofs, {}, model);
    const Skin& skin = tmpl.skins()[0];
    std::vector<glm::mat4> palette(skin.joints.size());
    computeSkinPalette(tmpl, skin, model, {}, palette);
    return palette;
}

struct Worst {
    double mm = 0.0;
    std::string where;
};

// Largest distance between a[i] and scale * b[i], millimetres.
Worst compare(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b, double scale) {
    Worst w;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
        const double mm = 1000.0 * glm::length(a[i] - scale * b[i]);
        if (mm > w.mm) w.mm = mm, w.where = "vertex " + std::to_string(i);
    }
    return w;
}

// The vertex counts of the primitives Throng merged into its skinned mesh, in order.
std::vector<std::size_t> throngPrimitiveVertices(const CharacterAsset& asset, const LoadedCharacter& ch) {
    std::vector<std::size_t> n;
    for (int p : ch.primitives) n.push_back(asset.primitives[std::size_t(p)].data->vertexCount());
    return n;
}

class PoseOracleTest : public ::testing::TestWithParam<OracleCharacter> {};

TEST_P(PoseOracleTest, SkinnedVerticesAgreeWithVtk) {
    const OracleCharacter& c = GetParam();
    const CharacterAsset& asset = test::loadedCharacter(c.file, c.scale);
    const LoadedCharacter* ch = nullptr;
    for (const LoadedCharacter& l : asset.characters)
        if (l.skin >= 0 && !ch) ch = &l;
    ASSERT_TRUE(ch) << c.file << " has no skinned character";
    const auto& tmpl = ch->tmpl;
    test::VtkGltfPoser vtk(test::characterPath(c.file));
    ASSERT_EQ(vtk.animationCount(), int(asset.animations.size()));

    Worst overall;
    {
        // At rest: no animation applied (the node hierarchy, inverse binds and skinning alone).
        testkit::Stage stage(tmpl, 0);
        stage.processor.processFrame(*stage.root, farCamera(stage.crowd.skeletonRootRadius(stage.id)), 0.0);
        const std::vector<glm::dvec3> throng = test::drawnPositions(stage.processor.drawList(), clampedPalette(*tmpl, -1, 0.0));
        const test::VtkPosedMesh posed = vtk.pose(-1, 0.0);
        ASSERT_EQ(throng.size(), posed.positions.size());
        overall = compare(throng, posed.positions, c.scale);
        EXPECT_LE(overall.mm, kToleranceMm) << "at rest, " << overall.where << " is " << overall.mm << " mm from VTK's";
        overall.where = "rest, " + overall.where;
    }
    for (const std::string& name : c.clips) {
        SCOPED_TRACE(std::string(c.file) + " clip '" + name + "'");
        const int clip = name.empty() ? 0 : tmpl->findClip(name);
        ASSERT_GE(clip, 0);
        const int animation = ch->clipSource[std::size_t(clip)];
        const double d = tmpl->clips()[std::size_t(clip)]->duration();
        EXPECT_NEAR(vtk.duration(animation), d, 1e-6) << "the two readings disagree on the clip's duration";
        testkit::Stage stage(tmpl, clip);
        const Camera far = farCamera(stage.crowd.skeletonRootRadius(stage.id));
        Worst clipWorst;
        for (const Sample& s : samplesOf(d)) {
            SCOPED_TRACE(s.label);
            stage.processor.processFrame(*stage.root, far, s.throngTime);
            const DrawList& list = stage.processor.drawList();
            ASSERT_EQ(list.size(), 1u) << "one skinned mesh expected";
            // The Skeleton Root of an actor at the origin is the world origin: the frames agree.
            EXPECT_EQ(list.items()[0].world.toMat4(), Mat4(1.0));
            const std::vector<glm::mat4> clamped = s.looped ? std::vector<glm::mat4>{} : clampedPalette(*tmpl, clip, s.throngTime);
            const std::vector<glm::dvec3> throng = test::drawnPositions(list, clamped);
            const test::VtkPosedMesh posed = vtk.pose(animation, s.vtkTime);
            ASSERT_EQ(posed.primitiveVertices, throngPrimitiveVertices(asset, *ch)) << "primitives do not match one to one";
            ASSERT_EQ(throng.size(), posed.positions.size());
            const Worst w = compare(throng, posed.positions, c.scale);
            EXPECT_LE(w.mm, kToleranceMm) << w.where << " is " << w.mm << " mm from VTK's";
            if (w.mm > clipWorst.mm) clipWorst = {w.mm, s.label + ", " + w.where};
        }
        std::cout << "[ oracle   ] " << c.file << " '" << tmpl->clips()[std::size_t(clip)]->name() << "' (" << d
                  << " s): worst vertex error " << std::setprecision(3) << clipWorst.mm << " mm (" << clipWorst.where << ")\n";
        if (clipWorst.mm > overall.mm) overall = {clipWorst.mm, name + ", " + clipWorst.where};
    }
    RecordProperty("worst_vertex_error_mm", std::to_string(overall.mm));
    std::cout << "[ oracle   ] " << c.file << ": worst vertex error " << overall.mm << " mm, tolerance " << kToleranceMm
              << " mm\n";
}

// The negative control: one joint (the one most vertices follow) turned by 1 degree about its own
// origin is seen by the vertex comparison.
TEST_P(PoseOracleTest, OneJointTurnedByOneDegreeIsDetected) {
    const OracleCharacter& c = GetParam();
    const CharacterAsset& asset = test::loadedCharacter(c.file, c.scale);
    const auto tmpl = asset.primaryTemplate();
    ASSERT_TRUE(tmpl);
    const LoadedCharacter& ch = asset.characters.front();
    const int clip = c.clips.front().empty() ? 0 : tmpl->findClip(c.clips.front());
    const double t = 0.37 * tmpl->clips()[std::size_t(clip)]->duration();
    testkit::Stage stage(tmpl, clip);
    stage.processor.processFrame(*stage.root, farCamera(stage.crowd.skeletonRootRadius(stage.id)), t);
    ASSERT_EQ(stage.processor.drawList().size(), 1u);
    const DrawItem& item = stage.processor.drawList().items()[0];
    ASSERT_TRUE(item.skinPalette);
    const auto& mesh = dynamic_cast<const MeshDrawable&>(*item.drawable).mesh();
    std::vector<glm::mat4> palette(item.skinPalette, item.skinPalette + item.skinPaletteSize);
    const std::uint32_t k = test::busiestJoint(mesh);
    const SkeletonNode& joint = tmpl->nodes()[tmpl->skins()[0].joints[k]];
    palette[k] = test::rotatedAboutJoint(palette[k], joint.inverseBind, std::numbers::pi / 180.0, glm::dvec3(1, 0, 0));

    test::VtkGltfPoser vtk(test::characterPath(c.file));
    const test::VtkPosedMesh posed = vtk.pose(ch.clipSource[std::size_t(clip)], t);
    const Worst unperturbed = compare(test::drawnPositions(stage.processor.drawList()), posed.positions, c.scale);
    const Worst perturbed = compare(test::drawnPositions(stage.processor.drawList(), palette), posed.positions, c.scale);
    EXPECT_LE(unperturbed.mm, kToleranceMm);
    EXPECT_GT(perturbed.mm, kToleranceMm) << "joint '" << joint.name << "' turned by 1 degree went unnoticed";
    std::cout << "[ oracle   ] " << c.file << ": joint '" << joint.name << "' turned by 1 degree: worst vertex error "
              << perturbed.mm << " mm (unperturbed " << unperturbed.mm << " mm)\n";
}

INSTANTIATE_TEST_SUITE_P(Characters, PoseOracleTest, ::testing::ValuesIn(kCharacters),
                         [](const ::testing::TestParamInfo<OracleCharacter>& p) {
                             std::string n = p.param.file;
                             return n.substr(0, n.find('.'));
                         });

}  // namespace
}  // namespace throng
