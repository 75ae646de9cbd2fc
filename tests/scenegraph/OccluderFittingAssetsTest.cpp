// Occluder boxes fitted inside the real town tiles (Kenney City Builder, loaded as the town loads
// them): thousands of segments from eyes outside each model's bounding box, many grazing its faces,
// to points on the boxes must each cross a front face of the model before they reach the box.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "OccluderOracle.h"
#include "throng/testkit/Assets.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/scenegraph/OccluderFitting.h"

using namespace throng;
using throng::testkit::TriangleSoup;

namespace {

const std::string kTiles = testkit::sharedAssets() + "/town/kenney_city_builder";

std::vector<std::string> tileFiles() {
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(kTiles))
        if (entry.path().extension() == ".glb") files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    return files;
}

struct Model {
    CharacterAsset asset;
    std::vector<const MeshData*> meshes;
};

Model load(const std::string& file) {
    Model m;
    m.asset = loadCharacter(kTiles + "/" + file);
    for (const auto& p : m.asset.primitives) m.meshes.push_back(p.data.get());
    return m;
}

std::string describe(const glm::dvec3& p) {
    char text[96];
    std::snprintf(text, sizeof text, "(%.4f, %.4f, %.4f)", p.x, p.y, p.z);
    return text;
}

}  // namespace

TEST(OccluderFittingAssets, BoxesOfEveryTownTileAreHiddenBehindFrontFaces) {
    const auto files = tileFiles();
    ASSERT_GE(files.size(), 15u) << "town tiles missing in " << kTiles;
    int buildingsWithBoxes = 0;
    for (const std::string& file : files) {
        const Model model = load(file);
        OccluderFitStatistics stats;
        const auto boxes = fitOccluderBoxes(model.meshes, {}, &stats);
        const TriangleSoup soup(model.meshes);
        const auto report = throng::testkit::probeBoxes(soup, boxes, 4000, std::hash<std::string>{}(file));
        std::printf("%-30s %6zu triangles, grid %dx%dx%d, solid cells %6zu (%5.1f %% of bounds), %zu boxes, %5.1f %% of bounds; "
                    "%d segments, %d first crossing a back face, %d unseen\n",
                    file.c_str(), soup.count(), stats.cells.x, stats.cells.y, stats.cells.z, stats.solidCells,
                    100.0 * stats.solidVolume / stats.boundsVolume, boxes.size(), 100.0 * stats.boxVolume / stats.boundsVolume,
                    report.segments, report.backFirst, report.misses);
        for (const AxisBox& b : boxes)
            std::printf("    box %s .. %s\n", describe(glm::dvec3(b.min)).c_str(), describe(glm::dvec3(b.max)).c_str());
        EXPECT_EQ(report.misses, 0) << file << ": " << report.misses << " of " << report.segments << " segments reach a box unseen";
        for (const auto& miss : report.examples)
            ADD_FAILURE() << file << ": eye " << describe(miss.eye) << " sees box point " << describe(miss.target)
                          << (miss.anyHit ? " through back faces only" : " crossing nothing");
        for (const AxisBox& b : boxes) {
            EXPECT_TRUE(b.min.x >= soup.lo().x && b.max.x <= soup.hi().x && b.min.y >= soup.lo().y && b.max.y <= soup.hi().y &&
                        b.min.z >= soup.lo().z && b.max.z <= soup.hi().z)
                << file;
        }
        if (file.rfind("building-", 0) == 0 && !boxes.empty()) ++buildingsWithBoxes;
    }
    // Buildings are the town's occluders: every one of them must get a box.
    EXPECT_EQ(buildingsWithBoxes, 5);
}

TEST(OccluderFittingAssets, OracleCatchesBoxesPushedOutOfTheBuildings) {
    // The same probe on each building's largest box moved out by two cells: the box now crosses
    // the building's walls, and the oracle must see it.
    for (const std::string file : {"building-garage.glb", "building-small-a.glb", "building-small-b.glb", "building-small-c.glb", "building-small-d.glb"}) {
        const Model model = load(file);
        OccluderFitStatistics stats;
        const auto boxes = fitOccluderBoxes(model.meshes, {}, &stats);
        ASSERT_FALSE(boxes.empty()) << file;
        const float out = 2.0f * std::max({stats.cellSize.x, stats.cellSize.y, stats.cellSize.z});
        const AxisBox inflated = boxes[0].shrunk(-out);
        const TriangleSoup soup(model.meshes);
        const auto report = throng::testkit::probeBoxes(soup, std::span<const AxisBox>(&inflated, 1), 2000, 5);
        EXPECT_GT(report.misses, 0) << file << ": a box " << out << " larger than fitted is never seen";
        std::printf("%-30s box moved out by %.3f: %d of %d segments reach it unseen\n", file.c_str(), double(out), report.misses, report.segments);
    }
}
