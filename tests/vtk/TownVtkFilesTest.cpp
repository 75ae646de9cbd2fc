// throng-town --vtk on a small town that exercises every tier (meshes, key-pose caches, impostors)
// and occlusion: the files read back with VTK's readers agree with the program's own stats.csv and
// summary.json for the same frames.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>
#include <vtkCell.h>

#include "VtkFiles.h"

using namespace throng::testkit;
namespace fs = std::filesystem;

namespace {

constexpr int kFrames = 21;
constexpr int kEvery = 10;

// stats.csv: one map of column to value per frame.
std::vector<std::map<std::string, std::string>> readStats(const fs::path& path) {
    std::ifstream in(path);
    std::string line;
    std::vector<std::string> header;
    std::vector<std::map<std::string, std::string>> rows;
    auto split = [](const std::string& s) {
        std::vector<std::string> cells;
        std::stringstream ss(s);
        for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
        return cells;
    };
    if (std::getline(in, line)) header = split(line);
    while (std::getline(in, line)) {
        const auto cells = split(line);
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
        rows.push_back(std::move(row));
    }
    return rows;
}

// Runs throng-town once per test (CTest runs each case as its own process, possibly two at once:
// each has its own folder).
class TownVtkFiles : public ::testing::Test {
protected:
    void SetUp() override {
        work_ = fs::path(THRONG_TEST_OUTPUT_DIR) / ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(work_);
        fs::create_directories(work_);
        const std::string command = std::string("\"") + THRONG_TOWN_EXE + "\" --scene \"" + THRONG_TOWN_SCENE +
                                    "\" --headless --frames " + std::to_string(kFrames) +
                                    " --every 0 --width 320 --height 180 --out \"" + (work_ / "out").string() + "\" --vtk \"" +
                                    (work_ / "vtk").string() + "\" --vtk-every " + std::to_string(kEvery) + " 2> \"" +
                                    (work_ / "town.log").string() + "\"";
        ASSERT_EQ(std::system(command.c_str()), 0) << "throng-town failed; see " << (work_ / "town.log");
        stats_ = readStats(work_ / "out" / "stats.csv");
        ASSERT_EQ(stats_.size(), std::size_t(kFrames));
        std::ifstream(work_ / "out" / "summary.json") >> summary_;
    }
    double stat(int frame, const char* column) const { return std::stod(stats_.at(std::size_t(frame)).at(column)); }
    fs::path vtk(const std::string& name) const { return work_ / "vtk" / name; }

    fs::path work_;
    std::vector<std::map<std::string, std::string>> stats_;
    nlohmann::json summary_;
};

std::size_t countOf(const std::vector<double>& v, double value) { return std::size_t(std::count(v.begin(), v.end(), value)); }

}  // namespace

TEST_F(TownVtkFiles, EveryFrameWrittenHasEveryActorAndAgreesWithStats) {
    const std::vector<PvdEntry> pvd = readPvd(vtk("crowd.pvd"));
    std::vector<int> written;
    for (int f = 0; f < kFrames; f += kEvery) written.push_back(f);
    ASSERT_EQ(pvd.size(), written.size()) << "the collection lists every frame written";
    std::size_t impostors = 0, cached = 0, occluded = 0, meshes = 0;
    for (std::size_t k = 0; k < written.size(); ++k) {
        const int f = written[k];
        SCOPED_TRACE("frame " + std::to_string(f));
        char name[64];
        std::snprintf(name, sizeof name, "actors_%06d.vtp", f);
        EXPECT_EQ(pvd[k].file, name);
        EXPECT_NEAR(pvd[k].time, stat(f, "time"), 1e-5);  // stats.csv keeps 6 digits
        const auto data = readPolyData(vtk(name));
        ASSERT_TRUE(data);
        // One point per actor alive in the frame.
        EXPECT_EQ(data->GetNumberOfPoints(), vtkIdType(stat(f, "actors_in_scene")));
        EXPECT_EQ(data->GetNumberOfPoints(), summary_["actors"].get<vtkIdType>());
        for (const char* array : {"id", "group", "template", "tier", "lod", "behaviour_level", "speed", "cascade_class", "rejected_at"})
            EXPECT_EQ(pointValues(*data, array).size(), std::size_t(data->GetNumberOfPoints())) << array;
        const auto tier = pointValues(*data, "tier"), rejected = pointValues(*data, "rejected_at");
        const auto group = pointValues(*data, "group"), speed = pointValues(*data, "speed");
        // Where the cascade left each actor, as the frame's own statistics count it.
        EXPECT_EQ(countOf(rejected, 1), std::size_t(stat(f, "culled_with_group")));
        EXPECT_EQ(countOf(rejected, 2), std::size_t(stat(f, "a")));
        EXPECT_EQ(countOf(rejected, 4), std::size_t(stat(f, "occluded_group") + stat(f, "occluded_refpoint") + stat(f, "occluded_sklsroot")));
        EXPECT_EQ(countOf(pointValues(*data, "cascade_class"), 3 /* B */), std::size_t(stat(f, "b")));
        // How DRAW got them.
        EXPECT_EQ(countOf(tier, 2), std::size_t(stat(f, "impostors")));
        EXPECT_EQ(countOf(tier, 1), std::size_t(stat(f, "key_pose_actors")));
        impostors += countOf(tier, 2), cached += countOf(tier, 1), meshes += countOf(tier, 0), occluded += countOf(rejected, 4);
        // Groups as the scene declares them.
        for (const auto& g : summary_["groups"]) {
            std::size_t members = 0;
            for (double v : group) members += v >= 0 && std::size_t(v) < summary_["groups"].size() && summary_["groups"][std::size_t(v)]["name"] == g["name"];
            EXPECT_EQ(members, g["actors"].get<std::size_t>()) << g["name"];
        }
        // Walkers and birds move at a few metres per second, never faster than a bird flies.
        if (f > 0) {
            EXPECT_GT(*std::max_element(speed.begin(), speed.end()), 0.5);
        }
        EXPECT_LT(*std::max_element(speed.begin(), speed.end()), 30.0);
    }
    EXPECT_GT(impostors, 0u);
    EXPECT_GT(cached, 0u);
    EXPECT_GT(meshes, 0u);
    EXPECT_GT(occluded, 0u) << "the scene should exercise every tier and occlusion";
}

TEST_F(TownVtkFiles, TownHasTheTilesTriangles) {
    const auto town = readPolyData(vtk("town.vtp"));
    ASSERT_TRUE(town);
    EXPECT_GT(town->GetNumberOfPolys(), 0);
    EXPECT_EQ(town->GetNumberOfPolys(), summary_["town"]["triangles"].get<vtkIdType>());
    double bounds[6];
    town->GetBounds(bounds);
    const double extent = summary_["town"]["tilesX"].get<double>() * summary_["town"]["tileSize"].get<double>();
    EXPECT_NEAR(bounds[1] - bounds[0], extent, 0.1 * extent);
}

TEST_F(TownVtkFiles, TrajectoriesHaveOnePolylinePerActor) {
    const auto trajectories = readPolyData(vtk("trajectories.vtp"));
    ASSERT_TRUE(trajectories);
    const auto actors = summary_["actors"].get<vtkIdType>();
    ASSERT_EQ(trajectories->GetNumberOfLines(), actors);
    const auto last = readPolyData(vtk("actors_000020.vtp"));
    ASSERT_TRUE(last);
    for (vtkIdType a = 0; a < actors; ++a) {
        vtkCell* line = trajectories->GetCell(a);
        ASSERT_EQ(line->GetNumberOfPoints(), 3);  // frames 0, 10, 20
        double p[3], q[3];
        trajectories->GetPoint(line->GetPointId(2), p);
        last->GetPoint(a, q);
        EXPECT_EQ(p[0], q[0]);
        EXPECT_EQ(p[1], q[1]);
        EXPECT_EQ(p[2], q[2]);
    }
}
