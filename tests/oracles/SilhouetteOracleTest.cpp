// Pictures checked against another implementation: the character golden images
// (tests/render/golden/character_*.png, kept by CharacterRenderTest, which only records what the
// renderer drew when they were made) and Throng's frames drawn the same way now (testkit::Stage,
// GlRenderer, GPU skinning, headless OSMesa, 160 x 160), against a CPU rasterisation (Silhouette.h)
// of the mesh VTK's vtkGLTFReader animates and skins, seen by the same camera.
//
// Frame: files loaded at their own scale (as the goldens: GltfLoadOptions::scale 1), the actor at
// the origin facing +Z, so the world frame is the glTF scene frame and VTK's points are used as
// they are. The camera is the golden's (Stage::frame: framed from Throng's posed mesh and
// Sklsroot radius); the oracle uses only its matrices.
//
// A silhouette is the set of pixels that differ from the clear colour (by more than 2/255 in some
// channel); the rasteriser covers a pixel whose centre lies in a projected triangle, as GL does.
// Frames pass at IoU >= 0.98. Measured with Mesa 22.3.6 llvmpipe: IoU 1 for CesiumMan and Fox (every
// pixel agrees), 0.9996 for the robot (one pixel of about 2700).
//
// Negative control: the head joint's palette entry turned by 10 degrees about its own origin (the
// rest of the skeleton as posed) must drop every golden view below 0.98. At 160 x 160 the
// silhouette is a coarse oracle: smaller turns, or turns of joints that move few pixels, stay
// above 0.98 (the vertex comparison in PoseOracleTest sees a 1 degree turn).

#include <gtest/gtest.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <numbers>

#include "throng/testkit/CharacterStage.h"
#include "Silhouette.h"
#include "ThrongPoses.h"
#include "VtkGltfPoser.h"
#include "throng/render/ImageIO.h"
#include "throng/render/OsMesaContext.h"
#include "throng/render/RendererOptions.h"

namespace throng {
namespace {

constexpr double kMinIoU = 0.98;
constexpr int kSize = testkit::kCharacterFrameSize;
constexpr double kDeg = std::numbers::pi / 180.0;

// The joint moving each character's head.
const std::map<std::string, std::string> kHeadJoint = {
    {"CesiumMan.glb", "Skeleton_neck_joint_2"}, {"Fox.glb", "b_Head_05"}, {"robot.glb", "Head"}};

glm::u8vec3 clearColour() {
    const glm::vec4 c = RendererOptions{}.clearColor;
    const auto level = [](float v) { return static_cast<std::uint8_t>(std::lround(v * 255.0f)); };
    return {level(c.r), level(c.g), level(c.b)};
}

void writeOutput(const Image& image, const std::string& name) {
    std::filesystem::create_directories(THRONG_TEST_OUTPUT_DIR);
    writePng(image, std::filesystem::path(THRONG_TEST_OUTPUT_DIR) / (name + ".png"));
}

// One golden view of one character, with VTK's reading of the same file.
struct View {
    const testkit::CharacterGoldenCase& c;
    const LoadedCharacter& character;
    int clip;
    testkit::Stage stage;
    test::VtkGltfPoser vtk;

    explicit View(const testkit::CharacterGoldenCase& gc)
        : c(gc),
          character(test::loadedCharacter(gc.file, 1.0).characters.front()),
          clip(std::string(gc.clip).empty() ? 0 : character.tmpl->findClip(gc.clip)),
          stage(character.tmpl, std::max(clip, 0)),
          vtk(test::characterPath(gc.file)) {}

    double duration() const { return character.tmpl->clips()[std::size_t(clip)]->duration(); }
    // The golden's camera for the pose at `time`.
    Camera camera(double time) { return stage.frame(time, c.azimuthDeg * kDeg, c.elevationDeg * kDeg); }
    // VTK's mesh at `time` rasterised from `camera`.
    test::Mask oracle(const Camera& camera, double time) {
        const test::VtkPosedMesh posed = vtk.pose(character.clipSource[std::size_t(clip)], time);
        return test::rasterise(posed.positions, posed.triangles, camera, kSize, kSize);
    }
};

class SilhouetteOracleTest : public ::testing::Test {
protected:
    std::shared_ptr<OsMesaContext> context = std::make_shared<OsMesaContext>(kSize, kSize);
    GlRenderer renderer{context};
};

TEST_F(SilhouetteOracleTest, GoldenImagesAndFramesMatchVtksMesh) {
    std::map<std::string, double> worst;
    for (const testkit::CharacterGoldenCase& c : testkit::kCharacterGoldenCases) {
        SCOPED_TRACE(c.golden);
        View view(c);
        ASSERT_GE(view.clip, 0) << "no clip " << c.clip;
        const Camera camera = view.camera(c.time);
        const test::Mask oracle = view.oracle(camera, c.time);
        const test::Mask drawn = test::silhouetteOf(view.stage.render(renderer, camera, c.time), clearColour());
        const Image golden = readPng(std::filesystem::path(THRONG_GOLDEN_DIR) / (std::string(c.golden) + ".png"));
        const test::Mask kept = test::silhouetteOf(golden, clearColour());
        const double drawnIoU = test::intersectionOverUnion(drawn, oracle);
        const double goldenIoU = test::intersectionOverUnion(kept, oracle);
        EXPECT_GE(goldenIoU, kMinIoU) << "the golden image disagrees with VTK's mesh";
        EXPECT_GE(drawnIoU, kMinIoU) << "the frame drawn now disagrees with VTK's mesh";
        if (std::min(drawnIoU, goldenIoU) < kMinIoU) {
            writeOutput(test::maskDifference(kept, oracle), std::string(c.golden) + "-golden-vs-vtk");
            writeOutput(test::maskDifference(drawn, oracle), std::string(c.golden) + "-drawn-vs-vtk");
        }
        std::cout << "[ oracle   ] " << c.golden << " (t = " << c.time << " s): IoU golden/VTK " << std::setprecision(4)
                  << goldenIoU << ", drawn/VTK " << drawnIoU << " (" << oracle.count() << " px)\n";
        double& w = worst.try_emplace(c.file, 1.0).first->second;
        w = std::min({w, drawnIoU, goldenIoU});
        // More of the clip from the same view: its start, middle and last key.
        for (double f : {0.0, 0.5, 1.0}) {
            const double t = f * view.duration();
            SCOPED_TRACE("t = " + std::to_string(t));
            const Camera at = view.camera(t);
            // Throng's actor loops (its clip time wraps to 0 at the end); glTF's last key holds.
            const test::Mask vtkMask = view.oracle(at, f < 1.0 ? t : 0.0);
            const double iou = test::intersectionOverUnion(test::silhouetteOf(view.stage.render(renderer, at, t), clearColour()), vtkMask);
            EXPECT_GE(iou, kMinIoU);
            w = std::min(w, iou);
        }
    }
    for (const auto& [file, iou] : worst) {
        RecordProperty("worst_iou_" + file.substr(0, file.find('.')), std::to_string(iou));
        std::cout << "[ oracle   ] " << file << ": worst IoU " << iou << " (required " << kMinIoU << ")\n";
    }
}

TEST_F(SilhouetteOracleTest, HeadTurnedByTenDegreesIsDetected) {
    for (const testkit::CharacterGoldenCase& c : testkit::kCharacterGoldenCases) {
        SCOPED_TRACE(c.golden);
        View view(c);
        ASSERT_GE(view.clip, 0);
        const ActorTemplate& tmpl = *view.character.tmpl;
        const Camera camera = view.camera(c.time);
        const test::Mask oracle = view.oracle(camera, c.time);
        const Image unperturbed = view.stage.render(renderer, camera, c.time);
        ASSERT_EQ(view.stage.processor.drawList().size(), 1u);
        DrawItem item = view.stage.processor.drawList().items()[0];
        std::vector<glm::mat4> palette(item.skinPalette, item.skinPalette + item.skinPaletteSize);
        const int head = tmpl.findNode(kHeadJoint.at(c.file));
        ASSERT_GE(head, 0);
        const auto& joints = tmpl.skins()[0].joints;
        const auto k = std::size_t(std::find(joints.begin(), joints.end(), std::uint32_t(head)) - joints.begin());
        ASSERT_LT(k, joints.size());
        palette[k] = test::rotatedAboutJoint(palette[k], tmpl.nodes()[std::size_t(head)].inverseBind, 10.0 * kDeg, glm::dvec3(1, 0, 0));
        item.skinPalette = palette.data();
        const Image perturbed = testkit::drawAlone(renderer, camera, item);
        const double before = test::intersectionOverUnion(test::silhouetteOf(unperturbed, clearColour()), oracle);
        const double after = test::intersectionOverUnion(test::silhouetteOf(perturbed, clearColour()), oracle);
        EXPECT_GE(before, kMinIoU);
        EXPECT_LT(after, kMinIoU) << "the head turned by 10 degrees went unnoticed";
        std::cout << "[ oracle   ] " << c.golden << ": head turned by 10 degrees: IoU " << std::setprecision(4) << after
                  << " (unperturbed " << before << ")\n";
    }
}

}  // namespace
}  // namespace throng
