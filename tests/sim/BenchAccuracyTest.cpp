// bench_accuracy end to end on a small crowd: the error of the frame is at its floor whenever a knob
// is switched off (PSNR 99 dB capped, SSIM 1, no pixel off, no joint error), and some setting of
// every knob that approximates shows an error, so each metric is wired to the frame and can fail.
// Occlusion culling is conservative, so every one of its rows must be at the floor too.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "throng/sim/AccuracyCsv.h"

using namespace throng::sim;

namespace {

const std::vector<std::string> kApproximating{"lod scale", "impostor distance", "key-pose cache rows", "render scale", "town lod scale"};

bool atFloor(const AccuracyRow& r) {
    const std::string& m = r.metric.name;
    if (m == "psnr") return r.metric.value == 99.0;
    if (m == "ssim") return r.metric.value > 1.0 - 1e-9;
    return r.metric.value == 0.0;  // pixels_off_8, joint_error_mean, joint_error_max
}

// One test (one run of the benchmark, ~25 s): CTest runs each test case as its own process.
TEST(BenchAccuracy, OffAtTheFloorAndEveryApproximationErrs) {
    const std::filesystem::path dir = THRONG_TEST_OUTPUT_DIR;
    std::filesystem::create_directories(dir);
    const std::filesystem::path csv = dir / "accuracy.csv", log = dir / "bench_accuracy.log";
    std::filesystem::remove(csv);
    const std::string command = std::string("\"") + THRONG_BENCH_ACCURACY + "\" --actors 120 --frames 1 --warmup 5 --width 320 "
                                "--height 180 --knobs lod-scale,impostor-distance,key-pose-rows,occlusion-resolution,render-scale,town-lod "
                                "--lod-scales 1,4 --impostor-distances 10,40 --cache-rows 4,32 --occlusion 64x36,256x144 "
                                "--render-scales 0.5 --town-lod-scales 3 "
                                "--accuracy-csv \"" + csv.string() + "\" > \"" + log.string() + "\" 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << "bench_accuracy failed; see " << log;
    const std::vector<AccuracyRow> rows = readAccuracyCsv(csv.string());
    const std::vector<std::string> knobs{"lod scale", "impostor distance", "key-pose cache rows", "occlusion resolution", "render scale",
                                         "town lod scale"};

    // Every row says what it measured.
    std::set<std::string> seenKnobs, cameras;
    for (const AccuracyRow& r : rows) {
        seenKnobs.insert(r.knob);
        cameras.insert(r.camera);
        EXPECT_EQ(r.scene, "default.json");
        EXPECT_GT(r.actors, 100);
        EXPECT_EQ(r.msPhase, "app_cull+draw");
        EXPECT_GT(r.ms, 0.0) << r.knob << " " << r.value;
    }
    EXPECT_EQ(seenKnobs, std::set<std::string>(knobs.begin(), knobs.end()));
    EXPECT_EQ(cameras, (std::set<std::string>{"street", "overview"}));

    // Switched off, every metric is at its floor.
    std::map<std::string, int> offRows;
    for (const AccuracyRow& r : rows) {
        if (!r.off) continue;
        ++offRows[r.knob];
        EXPECT_TRUE(atFloor(r)) << r.knob << " off, " << r.camera << ": " << r.metric.name << " = " << r.metric.value;
    }
    for (const std::string& knob : knobs) EXPECT_GE(offRows[knob], 6) << knob << ": PSNR, SSIM and pixels off on two cameras";
    EXPECT_GE(offRows["key-pose cache rows"], 10) << "the key-pose cache changes poses: joint error too";

    // Some setting of each approximating knob is off the floor in every metric it reports.
    for (const std::string& knob : kApproximating) {
        std::set<std::string> erring;
        for (const AccuracyRow& r : rows)
            if (r.knob == knob && !r.off && !atFloor(r)) erring.insert(r.metric.name);
        for (const char* metric : {"psnr", "ssim", "pixels_off_8"}) EXPECT_TRUE(erring.count(metric)) << knob << ": " << metric;
        if (knob == "key-pose cache rows") {
            EXPECT_TRUE(erring.count("joint_error_mean")) << knob;
            EXPECT_TRUE(erring.count("joint_error_max")) << knob;
        }
    }

    // Occlusion culling is conservative: whatever the buffer, the frame is the reference's.
    for (const AccuracyRow& r : rows) {
        if (r.knob != "occlusion resolution") continue;
        EXPECT_TRUE(atFloor(r)) << r.value << ", " << r.camera << ": " << r.metric.name << " = " << r.metric.value;
    }
}

}  // namespace
