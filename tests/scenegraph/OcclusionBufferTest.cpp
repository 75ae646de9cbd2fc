// The occlusion buffer: what it hides, and that it never hides what a ray from the eye can reach.

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <string>
#include <vector>
#include <cmath>
#include <limits>
#include <random>

#include "throng/testkit/Cameras.h"
#include "throng/scenegraph/AxisBox.h"
#include "throng/scenegraph/ByteStream.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/CullVisitor.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"
#include "throng/scenegraph/Occluder.h"
#include "throng/scenegraph/OcclusionBuffer.h"
#include "throng/scenegraph/OcclusionCulling.h"
#include "throng/scenegraph/TraditionalProcessor.h"
#include "throng/scenegraph/Transform.h"

namespace throng {
namespace {

std::array<Vec3, 8> corners(const Vec3& lo, const Vec3& hi) {
    std::array<Vec3, 8> c;
    for (int i = 0; i < 8; ++i) c[i] = Vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    return c;
}

Camera lookingDownMinusZ(double nearDistance = 0.1) {
    return testkit::lookingAt(Vec3(0, 0, 0), Vec3(0, 0, -1), {glm::radians(60.0), 16.0 / 9.0, nearDistance, 1000.0});
}

// A wall 20 m wide and 10 m high, 10 m in front of the eye, 1 m thick.
OcclusionBuffer wallBuffer(const Camera& camera) {
    OcclusionBuffer buffer(256, 144);
    buffer.begin(camera);
    EXPECT_TRUE(buffer.drawBox(corners(Vec3(-10, -5, -11), Vec3(10, 5, -10))));
    buffer.finish();
    return buffer;
}

TEST(OcclusionBuffer, HidesWhatIsWhollyBehindAnOccluderAndNothingElse) {
    const Camera camera = lookingDownMinusZ();
    const OcclusionBuffer buffer = wallBuffer(camera);
    EXPECT_TRUE(buffer.occluded(BoundingSphere(Vec3(0, 0, -20), 1.0)));     // right behind
    EXPECT_TRUE(buffer.occluded(BoundingSphere(Vec3(3, 2, -40), 2.0)));     // farther, off centre
    EXPECT_FALSE(buffer.occluded(BoundingSphere(Vec3(0, 0, -5), 1.0)));     // in front
    EXPECT_FALSE(buffer.occluded(BoundingSphere(Vec3(0, 0, -10.5), 1.0)));  // reaching into the wall's front
    EXPECT_FALSE(buffer.occluded(BoundingSphere(Vec3(19.5, 0, -20), 2.0))); // peeking past its edge
    EXPECT_FALSE(buffer.occluded(BoundingSphere(Vec3(0, 0, 5), 1.0)));      // behind the eye
    EXPECT_FALSE(buffer.occluded(BoundingSphere()));                        // empty
}

TEST(OcclusionBuffer, DepthIsTheOccludersFarthestFrontDepthOverThePixel) {
    const Camera camera = lookingDownMinusZ();
    const OcclusionBuffer buffer = wallBuffer(camera);
    // The wall's front face is at 10 m, square to the view: every covered pixel reads 10 m (a hair
    // more, the conservative direction), uncovered ones infinity.
    const double d = buffer.depthAt(128, 72);
    EXPECT_GE(d, 10.0);
    EXPECT_LT(d, 10.01);
    EXPECT_EQ(buffer.depthAt(0, 0), std::numeric_limits<double>::infinity());
    EXPECT_THROW((void)buffer.depthAt(256, 0), std::out_of_range);
}

TEST(OcclusionBuffer, AnOccluderTheEyeIsInsideDrawsNothing) {
    const Camera camera = lookingDownMinusZ();
    OcclusionBuffer buffer(64, 36);
    buffer.begin(camera);
    EXPECT_FALSE(buffer.drawBox(corners(Vec3(-1, -1, -1), Vec3(1, 1, 1))));
    buffer.finish();
    EXPECT_FALSE(buffer.occluded(BoundingSphere(Vec3(0, 0, -20), 1.0)));
    EXPECT_EQ(buffer.pixelsWritten(), 0u);
}

TEST(OcclusionBuffer, AnOccluderCutByTheNearPlaneStillHidesWhatIsBehindIt) {
    // A long wall beside and in front of the eye, from behind it to 30 m ahead, seen at a slant.
    Camera camera;
    camera.setPerspective(glm::radians(60.0), 16.0 / 9.0, 0.5, 1000.0);
    camera.setLookAt(Vec3(0, 1.7, 0), Vec3(5, 1.7, -10));
    OcclusionBuffer buffer(256, 144);
    buffer.begin(camera);
    EXPECT_TRUE(buffer.drawBox(corners(Vec3(2, 0, -30), Vec3(3, 10, 5))));
    buffer.finish();
    EXPECT_TRUE(buffer.occluded(BoundingSphere(Vec3(8, 1, -15), 0.8)));   // behind the wall
    EXPECT_FALSE(buffer.occluded(BoundingSphere(Vec3(1, 1, -15), 0.8)));  // on the eye's side
}

TEST(OcclusionBuffer, RejectsBadSizesAndNonPerspectiveCameras) {
    EXPECT_THROW(OcclusionBuffer(4, 100), std::invalid_argument);
    EXPECT_THROW(OcclusionBuffer(100, 5000), std::invalid_argument);
    try {
        OcclusionBuffer(100, 7);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("height"), std::string::npos) << e.what();
    }
    Camera ortho;
    ortho.setProjectionMatrix(glm::ortho(-1.0, 1.0, -1.0, 1.0, 0.1, 10.0));
    OcclusionBuffer buffer(64, 64);
    EXPECT_THROW(buffer.begin(ortho), std::invalid_argument);
    EXPECT_THROW(OcclusionCulling(OcclusionSettings{64, 64, 0}), std::invalid_argument);
    const auto refused = [](OcclusionSettings settings, const char* name) {
        try {
            OcclusionCulling stage(settings);
            ADD_FAILURE() << "accepted a bad '" << name << "'";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    };
    OcclusionSettings s;
    s.restFrames = -1;
    refused(s, "restFrames");
    s = OcclusionSettings{};
    s.restBelow = std::nan("");
    refused(s, "restBelow");
    s = OcclusionSettings{};
    s.wakeDistance = -1;
    refused(s, "wakeDistance");
    s = OcclusionSettings{};
    s.wakeAngleDegrees = 181;
    refused(s, "wakeAngleDegrees");
}

// Whether the segment from the origin to `p` passes through box [lo, hi] before reaching p (slab test).
bool blocked(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    double t0 = 0.0, t1 = 1.0;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(p[a]) < 1e-12) {
            if (0.0 < lo[a] || 0.0 > hi[a]) return false;
            continue;
        }
        double ta = lo[a] / p[a], tb = hi[a] / p[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return t0 < 1.0 - 1e-9;  // the box is entered before p is reached
}

// Random boxes and spheres seen from random eyes: whenever the buffer calls a sphere hidden, no ray
// from the eye to any of hundreds of points on the sphere's near side misses every box.
TEST(OcclusionBuffer, NeverHidesASphereThatARayFromTheEyeReaches) {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int hiddenChecked = 0;
    for (int scene = 0; scene < 300; ++scene) {
        Camera camera;
        camera.setPerspective(glm::radians(40.0 + 40.0 * (u(rng) + 1.0)), 1.0 + 0.8 * (u(rng) + 1.0), 0.2, 500.0);
        camera.setLookAt(Vec3(0), Vec3(u(rng), 0.5 * u(rng), -1.0));  // the eye at the origin keeps the oracle simple
        std::vector<std::pair<Vec3, Vec3>> boxes;
        OcclusionBuffer buffer(64 + int(64 * (u(rng) + 1.0)), 36 + int(36 * (u(rng) + 1.0)));
        buffer.begin(camera);
        for (int b = 0; b < 6; ++b) {
            const Vec3 c(8.0 * u(rng), 3.0 * u(rng), -6.0 - 6.0 * (u(rng) + 1.0));
            const Vec3 h(0.2 + 3.0 * (u(rng) + 1.0), 0.2 + 2.0 * (u(rng) + 1.0), 0.2 + 1.0 * (u(rng) + 1.0));
            boxes.emplace_back(c - h, c + h);
            buffer.drawBox(corners(c - h, c + h));
        }
        buffer.finish();
        for (int s = 0; s < 200; ++s) {
            const BoundingSphere sphere(Vec3(10.0 * u(rng), 5.0 * u(rng), -10.0 - 15.0 * (u(rng) + 1.0)), 0.05 + 1.5 * (u(rng) + 1.0));
            if (!buffer.occluded(sphere)) continue;
            ++hiddenChecked;
            for (int k = 0; k < 400; ++k) {
                Vec3 dir(u(rng), u(rng), u(rng));
                if (glm::length(dir) < 1e-3) continue;
                dir = glm::normalize(dir);
                if (glm::dot(dir, sphere.center()) > 0.0) dir = -dir;  // the side facing the eye
                const Vec3 p = sphere.center() + sphere.radius() * dir;
                const Vec4 clip = camera.viewProjection() * Vec4(p, 1.0);
                if (std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w) continue;  // off the screen: not the buffer's call
                bool anyBlocks = false;
                for (const auto& [lo, hi] : boxes) anyBlocks = anyBlocks || blocked(p, lo, hi);
                ASSERT_TRUE(anyBlocks) << "scene " << scene << ": a hidden sphere at (" << sphere.center().x << ", "
                                       << sphere.center().y << ", " << sphere.center().z << ") r " << sphere.radius()
                                       << " has a point the eye sees";
            }
        }
    }
    EXPECT_GT(hiddenChecked, 2000) << "too few hidden spheres to mean anything";
}

// occluded() looks at the pixel under a sphere's centre first; it must answer exactly as the test
// over the sphere's whole screen rectangle, for spheres of every size, near the screen's edges, off
// centre in off-axis projections, and from tiny (the shortcut is not taken) to near-plane sized.
TEST(OcclusionBuffer, TheCentrePixelShortcutAnswersAsTheWholeRectangle) {
    std::mt19937 rng(404);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int hidden = 0, visible = 0;
    for (int scene = 0; scene < 200; ++scene) {
        Camera camera;
        camera.setPerspective(glm::radians(30.0 + 50.0 * (u(rng) + 1.0)), 1.0 + 0.8 * (u(rng) + 1.0), 0.1 + 0.4 * (u(rng) + 1.0), 800.0);
        camera.setLookAt(Vec3(4.0 * u(rng), 2.0 * u(rng), 4.0 * u(rng)), Vec3(u(rng), 0.5 * u(rng), -1.0));
        OcclusionBuffer buffer(16 + int(200 * (u(rng) + 1.0)), 16 + int(100 * (u(rng) + 1.0)));
        buffer.begin(camera);
        for (int b = 0; b < 12; ++b) {
            const Vec3 c(12.0 * u(rng), 4.0 * u(rng), -5.0 - 15.0 * (u(rng) + 1.0));
            const Vec3 h(0.1 + 3.0 * (u(rng) + 1.0), 0.1 + 2.0 * (u(rng) + 1.0), 0.1 + 1.0 * (u(rng) + 1.0));
            buffer.drawBox(corners(c - h, c + h));
        }
        buffer.finish();
        for (int s = 0; s < 500; ++s) {
            const double size = std::pow(10.0, -4.0 + 5.0 * (u(rng) + 1.0) / 2.0);  // 0.1 mm to 10 m
            const BoundingSphere sphere(Vec3(40.0 * u(rng), 15.0 * u(rng), -0.5 - 40.0 * (u(rng) + 1.0)), size);
            const bool full = buffer.occludedOverRectangle(sphere);
            ASSERT_EQ(buffer.occluded(sphere), full) << "scene " << scene << ", sphere " << s;
            (full ? hidden : visible) += 1;
        }
    }
    EXPECT_GT(hidden, 5000);
    EXPECT_GT(visible, 5000);
}

// An Occluder node in a scene: CULL rejects the geometry behind it, and only that.
// A buffer sent to another process (write, read) answers every test there as where it was drawn;
// bytes of another size, cut short or holding a non-finite number are refused and change nothing.
TEST(OcclusionBuffer, ABufferReadFromItsBytesAnswersAsTheOriginal) {
    std::mt19937 rng(405);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Camera camera;
    camera.setPerspective(glm::radians(55.0), 1.6, 0.2, 800.0);
    camera.setLookAt(Vec3(1, 2, 3), Vec3(0.3, 0.1, -1.0));
    OcclusionBuffer drawn(256, 144), received(256, 144);
    drawn.begin(camera);
    for (int b = 0; b < 12; ++b) {
        const Vec3 c(12.0 * u(rng), 4.0 * u(rng), -5.0 - 15.0 * (u(rng) + 1.0));
        const Vec3 h(0.1 + 3.0 * (u(rng) + 1.0), 0.1 + 2.0 * (u(rng) + 1.0), 0.1 + 1.0 * (u(rng) + 1.0));
        drawn.drawBox(corners(c - h, c + h));
    }
    drawn.finish();
    std::vector<std::byte> bytes;
    ByteWriter out(bytes);
    drawn.write(out);
    ByteReader in(bytes, "rank 0's buffer");
    received.read(in);
    EXPECT_EQ(in.remaining(), 0u);
    int hidden = 0;
    for (int s = 0; s < 4000; ++s) {
        const BoundingSphere sphere(Vec3(40.0 * u(rng), 15.0 * u(rng), -0.5 - 40.0 * (u(rng) + 1.0)), 0.05 + 3.0 * (u(rng) + 1.0));
        ASSERT_EQ(received.occluded(sphere), drawn.occluded(sphere)) << "sphere " << s;
        hidden += drawn.occluded(sphere);
    }
    EXPECT_GT(hidden, 300);
    EXPECT_EQ(received.depthAt(128, 72), drawn.depthAt(128, 72));

    auto refusal = [&](OcclusionBuffer& into, const std::vector<std::byte>& b) {
        ByteReader r(b, "rank 0's buffer");
        try {
            into.read(r);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    OcclusionBuffer smaller(128, 72);
    EXPECT_NE(refusal(smaller, bytes).find("rank 0's buffer: an occlusion buffer of 256 x 144 pixels, this one has 128 x 72"),
              std::string::npos);
    OcclusionBuffer blank(256, 144);
    EXPECT_NE(refusal(blank, std::vector<std::byte>(bytes.begin(), bytes.end() - 1)).find("the bytes end at"), std::string::npos);
    std::vector<std::byte> bad = bytes;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(bad.data() + bad.size() - 4 * 300, &nan, sizeof nan);
    EXPECT_NE(refusal(blank, bad).find("depth at pixel"), std::string::npos);
    std::vector<std::byte> badCamera = bytes;
    const double inf = std::numeric_limits<double>::infinity();
    std::memcpy(badCamera.data() + 8, &inf, sizeof inf);
    EXPECT_NE(refusal(blank, badCamera).find("camera holds a number that is not finite"), std::string::npos);
    for (int x = 0; x < 256; x += 17)
        for (int y = 0; y < 144; y += 13) ASSERT_TRUE(std::isinf(blank.depthAt(x, y))) << "a refused read left depths behind";
}

TEST(OcclusionCulling, CullRejectsGenericNodesHiddenByAnOccluderNode) {
    auto root = std::make_shared<Group>();
    auto wall = std::make_shared<Transform>();
    wall->setMatrix(glm::translate(Mat4(1.0), Vec3(0, 0, -10)));
    wall->addChild(std::make_shared<Occluder>(std::vector<AxisBox>{AxisBox{glm::vec3(-3, -3, -0.5f), glm::vec3(3, 3, 0.5f)}},
                                              AxisBox{glm::vec3(-3.5f, -3.5f, -1), glm::vec3(3.5f, 3.5f, 1)}));
    root->addChild(wall);
    const auto cube = std::make_shared<MeshDrawable>(makeBox("cube", glm::vec3(0), glm::vec3(0.5f), glm::vec4(1)));
    const auto place = [&](const Vec3& at) {
        auto t = std::make_shared<Transform>();
        t->setMatrix(glm::translate(Mat4(1.0), at));
        t->addChild(std::make_shared<Geometry>(cube));
        root->addChild(t);
    };
    place(Vec3(0, 0, -30));   // hidden
    place(Vec3(0, 0, -5));    // in front
    place(Vec3(14, 0, -30));  // beside the wall, in view
    const Camera camera = lookingDownMinusZ();

    TraditionalProcessor plain, occluding;
    occluding.setOcclusion(OcclusionSettings{});
    const FrameStatistics a = plain.processFrame(*root, camera, 0.0);
    const FrameStatistics b = occluding.processFrame(*root, camera, 0.0);
    EXPECT_EQ(a.cull.drawItems, 3u);
    EXPECT_EQ(b.cull.drawItems, 2u);
    EXPECT_EQ(b.cull.nodesOccluded, 1u);
    EXPECT_EQ(b.occlusion.occludersDrawn, 1u);
    EXPECT_EQ(a.occlusion.occludersDrawn, 0u);  // off: nothing built, nothing drawn
    EXPECT_EQ(a.cull.occlusionTests, 0u);

    // With the eye inside the wall's shell the occluder is left out.
    Camera inside;
    inside.setPerspective(glm::radians(60.0), 16.0 / 9.0, 0.1, 1000.0);
    inside.setLookAt(Vec3(0, 0, -10.8), Vec3(0, 0, -30));
    const FrameStatistics c = occluding.processFrame(*root, inside, 0.0);
    EXPECT_EQ(c.occlusion.occludersInsideShell, 1u);
    EXPECT_EQ(c.cull.nodesOccluded, 0u);
}

// Gathering skips subtrees without Occluder nodes; one added later below such a subtree, deep down,
// is found again in the next frame, and so is one removed no longer.
TEST(OcclusionCulling, AnOccluderAddedBelowAnOccluderFreeSubtreeIsFound) {
    auto root = std::make_shared<Group>();
    auto outer = std::make_shared<Group>();
    auto inner = std::make_shared<Transform>();
    inner->setMatrix(glm::translate(Mat4(1.0), Vec3(0, 0, -10)));
    const auto cube = std::make_shared<MeshDrawable>(makeBox("cube", glm::vec3(0), glm::vec3(0.5f), glm::vec4(1)));
    inner->addChild(std::make_shared<Geometry>(cube));
    outer->addChild(inner);
    root->addChild(outer);
    auto behind = std::make_shared<Transform>();
    behind->setMatrix(glm::translate(Mat4(1.0), Vec3(0, 0, -30)));
    behind->addChild(std::make_shared<Geometry>(cube));
    root->addChild(behind);
    const Camera camera = lookingDownMinusZ();
    TraditionalProcessor occluding;
    occluding.setOcclusion(OcclusionSettings{});
    const FrameStatistics a = occluding.processFrame(*root, camera, 0.0);
    EXPECT_EQ(a.occlusion.occludersInView, 0u);
    EXPECT_FALSE(outer->mayHoldOccluders());  // merged: nothing below to gather
    EXPECT_FALSE(root->mayHoldOccluders());

    const auto wall = std::make_shared<Occluder>(std::vector<AxisBox>{AxisBox{glm::vec3(-3, -3, -0.5f), glm::vec3(3, 3, 0.5f)}},
                                                 AxisBox{glm::vec3(-3.5f, -3.5f, -1), glm::vec3(3.5f, 3.5f, 1)});
    inner->addChild(wall);
    const FrameStatistics b = occluding.processFrame(*root, camera, 0.0);
    EXPECT_EQ(b.occlusion.occludersDrawn, 1u);
    EXPECT_EQ(b.cull.nodesOccluded, 1u);  // the cube behind the wall
    EXPECT_TRUE(outer->mayHoldOccluders());

    inner->removeChild(wall.get());
    const FrameStatistics c = occluding.processFrame(*root, camera, 0.0);
    EXPECT_EQ(c.occlusion.occludersInView, 0u);
    EXPECT_EQ(c.cull.nodesOccluded, 0u);
    EXPECT_FALSE(outer->mayHoldOccluders());
}

// A view where occlusion hides little: with rest declared the stage then builds and tests nothing
// for restFrames frames (everything is drawn, as without occlusion), wakes when the camera moves or
// turns, and never rests where it hides much. Without rest declared it never rests.
TEST(OcclusionCulling, RestsAfterAFrameThatHidLittleUntilTheCameraMovesOrTurns) {
    auto root = std::make_shared<Group>();
    auto wall = std::make_shared<Transform>();
    wall->setMatrix(glm::translate(Mat4(1.0), Vec3(0, 0, -10)));
    wall->addChild(std::make_shared<Occluder>(std::vector<AxisBox>{AxisBox{glm::vec3(-1, -1, -0.5f), glm::vec3(1, 1, 0.5f)}},
                                              AxisBox{glm::vec3(-1.5f, -1.5f, -1), glm::vec3(1.5f, 1.5f, 1)}));
    root->addChild(wall);
    const auto cube = std::make_shared<MeshDrawable>(makeBox("cube", glm::vec3(0), glm::vec3(0.25f), glm::vec4(1)));
    const auto place = [&](const Vec3& at) {
        auto t = std::make_shared<Transform>();
        t->setMatrix(glm::translate(Mat4(1.0), at));
        t->addChild(std::make_shared<Geometry>(cube));
        root->addChild(t);
    };
    place(Vec3(0, 0, -30));  // the one hidden
    for (int i = 1; i <= 12; ++i) place(Vec3(-12.0 + 2.0 * i, 3.0, -30));  // above the wall, in view
    const Camera camera = lookingDownMinusZ();

    OcclusionSettings settings;
    settings.restFrames = 3;
    settings.restBelow = 0.2;
    TraditionalProcessor resting, always, plain;
    resting.setOcclusion(settings);
    always.setOcclusion(OcclusionSettings{});
    const FrameStatistics first = resting.processFrame(*root, camera, 0.0);
    EXPECT_FALSE(first.occlusion.rested);
    EXPECT_EQ(first.cull.nodesOccluded, 1u);
    ASSERT_LT(double(first.cull.nodesOccluded), 0.2 * double(first.cull.occlusionTests)) << "the view must hide little";
    const std::uint64_t drawnWithout = plain.processFrame(*root, camera, 0.0).cull.drawItems;
    for (int frame = 1; frame <= 3; ++frame) {
        const FrameStatistics s = resting.processFrame(*root, camera, 0.1 * frame);
        EXPECT_TRUE(s.occlusion.rested) << "frame " << frame;
        EXPECT_EQ(s.occlusion.occludersDrawn, 0u);
        EXPECT_EQ(s.cull.occlusionTests, 0u);
        EXPECT_EQ(s.cull.nodesOccluded, 0u);
        EXPECT_EQ(s.cull.drawItems, drawnWithout);
        EXPECT_FALSE(always.processFrame(*root, camera, 0.1 * frame).occlusion.rested);
    }
    const FrameStatistics after = resting.processFrame(*root, camera, 0.4);
    EXPECT_FALSE(after.occlusion.rested) << "the rest lasts restFrames frames";
    EXPECT_EQ(after.cull.nodesOccluded, 1u);

    // Resting again (it hid little again): a step past wakeDistance, or a turn past wakeAngle, wakes it.
    EXPECT_TRUE(resting.processFrame(*root, camera, 0.5).occlusion.rested);
    Camera moved;
    moved.setPerspective(glm::radians(60.0), 16.0 / 9.0, 0.1, 1000.0);
    moved.setLookAt(Vec3(0, 0, 2.5), Vec3(0, 0, -30));
    EXPECT_FALSE(resting.processFrame(*root, moved, 0.6).occlusion.rested);
    Camera nudged;  // within both limits of the frame just measured
    nudged.setPerspective(glm::radians(60.0), 16.0 / 9.0, 0.1, 1000.0);
    nudged.setLookAt(Vec3(0.5, 0, 2.5), Vec3(0.5, 0, -30));
    EXPECT_TRUE(resting.processFrame(*root, nudged, 0.7).occlusion.rested);
    Camera turned;
    turned.setPerspective(glm::radians(60.0), 16.0 / 9.0, 0.1, 1000.0);
    turned.setLookAt(Vec3(0, 0, 2.5), Vec3(-10, 0, -30));  // about 18 degrees
    EXPECT_FALSE(resting.processFrame(*root, turned, 0.8).occlusion.rested);

    // Where occlusion hides much it keeps testing.
    auto hidden = std::make_shared<Group>();
    auto wall2 = std::make_shared<Transform>();
    wall2->setMatrix(glm::translate(Mat4(1.0), Vec3(0, 0, -10)));
    wall2->addChild(std::make_shared<Occluder>(std::vector<AxisBox>{AxisBox{glm::vec3(-1, -1, -0.5f), glm::vec3(1, 1, 0.5f)}},
                                               AxisBox{glm::vec3(-1.5f, -1.5f, -1), glm::vec3(1.5f, 1.5f, 1)}));
    hidden->addChild(wall2);
    auto t = std::make_shared<Transform>();
    t->setMatrix(glm::translate(Mat4(1.0), Vec3(0, 0, -30)));
    t->addChild(std::make_shared<Geometry>(cube));
    hidden->addChild(t);
    TraditionalProcessor worthIt;
    worthIt.setOcclusion(settings);
    for (int frame = 0; frame < 5; ++frame) {
        const FrameStatistics s = worthIt.processFrame(*hidden, camera, 0.1 * frame);
        EXPECT_FALSE(s.occlusion.rested) << "frame " << frame;
        EXPECT_EQ(s.cull.nodesOccluded, 1u);
    }
}

TEST(OcclusionCulling, OccluderNodesRejectBadBoxes) {
    const AxisBox shell{glm::vec3(-1), glm::vec3(1)};
    EXPECT_THROW(Occluder({AxisBox{glm::vec3(0), glm::vec3(0)}}, shell), std::invalid_argument);
    EXPECT_THROW(Occluder({AxisBox{glm::vec3(-2), glm::vec3(0)}}, shell), std::invalid_argument);
    EXPECT_THROW(Occluder({AxisBox{glm::vec3(0), glm::vec3(std::nanf(""))}}, shell), std::invalid_argument);
    EXPECT_THROW(Occluder({}, AxisBox{}), std::invalid_argument);
    EXPECT_NO_THROW(Occluder({AxisBox{glm::vec3(-0.5f), glm::vec3(0.5f)}}, shell));
}

}  // namespace
}  // namespace throng
