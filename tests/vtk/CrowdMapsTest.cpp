// writeCrowdMaps' fundamental diagram on positions laid out by hand (people per cell and frame
// known), and readSpeedDensity's refusals, each naming the file and line.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "throng/vtk/CrowdMaps.h"

namespace fs = std::filesystem;

namespace {

fs::path freshFolder(const std::string& name) {
    const fs::path p = fs::path(THRONG_TEST_OUTPUT_DIR) / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

// The message of what `f` throws (empty if it throws nothing).
template <class F>
std::string messageOf(F f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(CrowdMaps, SpeedDensityCountsThePeopleSharingEachCellInEachFrame) {
    const fs::path dir = freshFolder("maps-speed-density");
    // 4 m cells from x = z = 0. Frame 0: three people in cell (0, 0) at 1 m/s, one alone in cell
    // (2, 0) at 2 m/s, one bird 12 m up at 9 m/s (not on the ground). Frame 1: the three have split
    // (two together in (0, 0) at 0.5 m/s, one joins the lone walker in (2, 0), both at 1.5 m/s).
    const std::vector<double> positions = {
        0.5, 0, 0.5,  1.5, 0, 1.5,  3.5, 0, 0.5,  9, 0, 1,  2, 12, 2,   // frame 0
        0.5, 0, 0.5,  1.5, 0, 1.5,  8.5, 0, 0.5,  9, 0, 1,  6, 12, 2};  // frame 1
    const std::vector<double> speeds = {1, 1, 1, 2, 9, 0.5, 0.5, 1.5, 1.5, 9};
    const std::vector<std::size_t> frames = {5, 5};
    const throng::vtk::CrowdMapSummary summary = throng::vtk::writeCrowdMaps(dir, positions, speeds, frames);
    EXPECT_DOUBLE_EQ(summary.peakLocalDensity, 3.0 / 16.0);

    const std::vector<throng::vtk::SpeedDensityRow> rows = throng::vtk::readSpeedDensity(dir / "speed_density.csv");
    ASSERT_EQ(rows.size(), 3u) << "cells held 1, 2 and 3 people";
    // One person alone: the lone walker of frame 0.
    EXPECT_EQ(rows[0].people, 1);
    EXPECT_EQ(rows[0].actorFrames, 1u);
    EXPECT_DOUBLE_EQ(rows[0].meanSpeed, 2.0);
    // Two together: the pair in (0, 0) at 0.5 and the pair in (2, 0) at 1.5, both in frame 1.
    EXPECT_EQ(rows[1].people, 2);
    EXPECT_DOUBLE_EQ(rows[1].density, 2.0 / 16.0);
    EXPECT_EQ(rows[1].actorFrames, 4u);
    EXPECT_DOUBLE_EQ(rows[1].meanSpeed, 1.0);
    // Three: frame 0's group.
    EXPECT_EQ(rows[2].people, 3);
    EXPECT_EQ(rows[2].actorFrames, 3u);
    EXPECT_DOUBLE_EQ(rows[2].meanSpeed, 1.0);
    EXPECT_DOUBLE_EQ(rows[0].share + rows[1].share + rows[2].share, 1.0) << "the birds are not on the ground";
    EXPECT_DOUBLE_EQ(rows[1].share, 4.0 / 8.0);
}

TEST(CrowdMaps, FramesThatDoNotHoldTheSamplesAreRefused) {
    const fs::path dir = freshFolder("maps-bad-frames");
    const std::vector<double> positions = {0, 0, 0, 1, 0, 1};
    const std::vector<double> speeds = {1, 1};
    const std::vector<std::size_t> frames = {1, 2};
    EXPECT_NE(messageOf([&] { throng::vtk::writeCrowdMaps(dir, positions, speeds, frames); }).find("3 actor-frames, not the 2"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "crowd_maps.vti")) << "nothing half-written";
}

TEST(CrowdMaps, ReadSpeedDensityNamesTheFileAndLineOfABadRow) {
    const fs::path dir = freshFolder("maps-bad-csv");
    auto refusal = [&](const std::string& text) {
        const fs::path file = dir / "speed_density.csv";
        std::ofstream(file) << text;
        return messageOf([&] { throng::vtk::readSpeedDensity(file); });
    };
    const std::string header = "people,density_per_m2,actor_frames,share,mean_speed_m_s\n";
    EXPECT_NE(refusal("people,speed\n").find("speed_density.csv:1: expected the header"), std::string::npos);
    EXPECT_NE(refusal(header + "1,0.0625,3,0.5,1.2\n2,0.125,x,0.5,1\n").find("speed_density.csv:3: field 3 ('x')"), std::string::npos);
    EXPECT_NE(refusal(header + "1,0.0625,3,0.5\n").find(":2: 4 fields, not 5"), std::string::npos);
    EXPECT_NE(refusal(header + "2,0.125,3,0.5,1\n1,0.0625,3,0.5,1\n").find(":3: people must grow"), std::string::npos);
    EXPECT_NE(refusal(header + "1.5,0.1,3,0.5,1\n").find(":2: people and actor-frames must be whole"), std::string::npos);
    EXPECT_NE(refusal(header + "1,nan,3,0.5,1\n").find(":2: field 2"), std::string::npos);
    EXPECT_NE(messageOf([&] { throng::vtk::readSpeedDensity(dir / "absent.csv"); }).find("absent.csv: cannot be read"), std::string::npos);
    EXPECT_TRUE(refusal(header).empty()) << "a run that recorded nobody on the ground has no rows";
}
