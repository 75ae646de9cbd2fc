// Scene files: a valid one parses into what it says; every malformed one (wrong types, missing
// fields, unknown keys and behaviours, negative counts, missing assets) gives a SceneError with
// the JSON path of the problem.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <string>
#include <vector>

#include "throng/testkit/Assets.h"
#include "throng/sim/CrowdLooks.h"
#include "throng/sim/SceneError.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/SceneRanges.h"

using namespace throng::sim;

namespace {

const std::string kAssets = throng::testkit::sharedAssets();

// A valid scene; `patch` replaces one piece of it to break it.
std::string scene(const std::string& actors, const std::string& extra = "") {
    return R"({
  "name": "test",
  "seed": 3,
  "town": {"blocksX": 2, "blocksZ": 2, "tiles": "town/kenney_city_builder"},
  "templates": {
    "cesium": {"gltf": "characters/CesiumMan.glb", "walkClipSpeed": 1.3},
    "person": {"procedural": "seed-humanoid", "walkClip": "walk"}
  },
  "actors": )" + actors + extra + R"(
})";
}

const std::string kActors = R"([
    {"template": "cesium", "count": 100, "behaviour": "walk", "speed": [1.1, 1.5]},
    {"template": "person", "count": 12, "behaviour": "idle", "groupSize": [3, 4], "levels": [20, 60]}
  ])";

}  // namespace

TEST(SceneParser, AValidSceneSaysWhatItDeclares) {
    const SceneDescription s = parseScene(scene(kActors, R"(,
  "effects": {"avoidance": true, "gaze": {"levels": [10, 30], "range": 6}},
  "representation": {"impostorDistance": 90, "hysteresis": 0.2},
  "camera": {"fov": 50, "path": [{"time": 0, "eye": [0, 20, 40], "target": [0, 0, 0]}, {"time": 10, "eye": [40, 20, 0], "target": [0, 0, 0]}]})"),
                                          kAssets);
    EXPECT_EQ(s.name, "test");
    EXPECT_EQ(s.seed, 3u);
    ASSERT_TRUE(s.town.has_value());
    EXPECT_EQ(s.town->blocksX, 2);
    EXPECT_EQ(s.templates.size(), 2u);
    EXPECT_NE(s.templates.at("cesium").gltf.find("CesiumMan.glb"), std::string::npos);
    EXPECT_DOUBLE_EQ(s.templates.at("cesium").walkClipSpeed, 1.3);
    ASSERT_EQ(s.actors.size(), 2u);
    EXPECT_EQ(s.actors[0].count, 100);
    EXPECT_EQ(s.actors[1].behaviour, "idle");
    EXPECT_EQ(s.actors[1].groupSize.y, 4);
    EXPECT_EQ(s.actors[1].levels, (std::vector<double>{20, 60}));
    EXPECT_TRUE(s.effects.avoidance);
    EXPECT_TRUE(s.effects.gaze);
    EXPECT_DOUBLE_EQ(s.effects.gazeRange, 6.0);
    EXPECT_DOUBLE_EQ(s.representation.impostorDistance, 90.0);
    ASSERT_EQ(s.camera.path.size(), 2u);
    EXPECT_DOUBLE_EQ(s.camera.path[1].eye.x, 40.0);
    // Effects not declared stay off.
    const SceneDescription plain = parseScene(scene(kActors), kAssets);
    EXPECT_FALSE(plain.effects.avoidance);
    EXPECT_FALSE(plain.effects.gaze);
    EXPECT_TRUE(plain.town->lod.empty()) << "no town LOD unless declared";
}

TEST(SceneParser, TownLodLevelsAreRead) {
    std::string text = scene(kActors);
    const std::string tiles = R"("tiles": "town/kenney_city_builder")";
    text.replace(text.find(tiles), tiles.size(), tiles + R"(, "lod": [{"until": 50}, {"until": 100, "triangles": 0.5}, {"triangles": 0.25}])");
    const SceneDescription s = parseScene(text, kAssets);
    ASSERT_EQ(s.town->lod.size(), 3u);
    EXPECT_DOUBLE_EQ(s.town->lod[0].x, 50.0);
    EXPECT_DOUBLE_EQ(s.town->lod[0].y, 1.0);
    EXPECT_DOUBLE_EQ(s.town->lod[1].y, 0.5);
    EXPECT_TRUE(std::isinf(s.town->lod[2].x));
    EXPECT_DOUBLE_EQ(s.town->lod[2].y, 0.25);
}

struct BadScene {
    const char* what;
    std::string text;
    std::string path;
    const char* reason;
    bool scratch = false;  // paths resolve in scratchFolder() rather than the shared assets
};

// Test names and failures show what the case is, not its bytes.
void PrintTo(const BadScene& b, std::ostream* os) { *os << b.what; }

// A folder of files that are not glTF characters: empty.glb (0 bytes), text.glb (a note),
// folder.glb (a folder). Made once, removed when the tests end.
const std::string& scratchFolder() {
    struct Folder {
        std::filesystem::path path = std::filesystem::temp_directory_path() / ("throng-scene-test-" + std::to_string(::getpid()));
        Folder() {
            std::filesystem::create_directories(path / "folder.glb");
            std::ofstream(path / "empty.glb").flush();
            std::ofstream(path / "text.glb") << "These are notes about a character, not the character.\n";
        }
        ~Folder() {
            std::error_code ec;
            std::filesystem::remove_all(path, ec);
        }
    };
    static const Folder folder;
    static const std::string text = folder.path.string();
    return text;
}

// One template `x` with `field` (a JSON fragment) beside a procedural source, and `actors`.
std::string birds(const std::string& field, const std::string& actors = "[]") {
    return R"({"templates": {"x": {"procedural": "bird")" + field + R"(}}, "actors": )" + actors + "}";
}

class SceneParserErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneParserErrors, NamesThePathAndTheReason) {
    const BadScene& b = GetParam();
    try {
        parseScene(b.text, b.scratch ? scratchFolder() : kAssets, "scene.json");
        FAIL() << b.what << ": accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.path(), b.path) << b.what << ": " << e.what();
        EXPECT_NE(e.reason().find(b.reason), std::string::npos) << b.what << ": " << e.what();
        EXPECT_NE(std::string(e.what()).find("scene.json"), std::string::npos);
    }
}

INSTANTIATE_TEST_SUITE_P(
    MalformedScenes, SceneParserErrors,
    ::testing::Values(
        BadScene{"not JSON", "{\"actors\": [1, 2,,]}", "", "line 1"},
        BadScene{"count of the wrong type", scene(R"([{"template": "cesium", "count": "many", "behaviour": "walk"}])"),
                 "/actors/0/count", "must be an integer"},
        BadScene{"negative count", scene(R"([{"template": "cesium", "count": -5, "behaviour": "walk"}])"), "/actors/0/count",
                 "must be from 0 to 2000000, got -5"},
        BadScene{"missing behaviour", scene(R"([{"template": "cesium", "count": 5}])"), "/actors/0/behaviour", "missing"},
        BadScene{"unknown behaviour", scene(R"([{"template": "cesium", "count": 5, "behaviour": "dance"}])"),
                 "/actors/0/behaviour", "'dance' is not a behaviour"},
        BadScene{"unknown template", scene(R"([{"template": "robot", "count": 5, "behaviour": "walk"}])"),
                 "/actors/0/template", "no declared template"},
        BadScene{"unknown field", scene(R"([{"template": "cesium", "count": 5, "behaviour": "walk", "colour": 3}])"),
                 "/actors/0/colour", "not a known field"},
        BadScene{"actors not an array", scene(R"({"template": "cesium"})"), "/actors", "must be an array"},
        BadScene{"bad speed range", scene(R"([{"template": "cesium", "count": 5, "behaviour": "walk", "speed": [2, 1]}])"),
                 "/actors/0/speed", "min <= max"},
        BadScene{"looks on a procedural template", birds(R"(, "looks": 4)"), "/templates/x", "'looks' apply to glTF templates only"},
        BadScene{"too many generated looks", R"({"templates": {"c": {"gltf": "characters/CesiumMan.glb", "looks": 241}}, "actors": []})",
                 "/templates/c/looks", "must be from 1 to 240"},
        BadScene{"no looks", R"({"templates": {"c": {"gltf": "characters/CesiumMan.glb", "looks": []}}, "actors": []})",
                 "/templates/c/looks", "must list at least one look"},
        BadScene{"a look's colour malformed",
                 R"({"templates": {"c": {"gltf": "characters/CesiumMan.glb", "looks": [{"skin": "#ffcc99", "hair": "brown", "top": "#000000", "bottom": "#000000"}]}}, "actors": []})",
                 "/templates/c/looks/0/hair", "'brown' is not a colour \"#rrggbb\""},
        BadScene{"a look without its bottom",
                 R"({"templates": {"c": {"gltf": "characters/CesiumMan.glb", "looks": [{"skin": "#ffcc99", "hair": "#101010", "top": "#000000"}]}}, "actors": []})",
                 "/templates/c/looks/0/bottom", "is missing"},
        BadScene{"levels not increasing", scene(R"([{"template": "cesium", "count": 5, "behaviour": "walk", "levels": [30, 20]}])"),
                 "/actors/0/levels/1", "must increase"},
        BadScene{"missing asset",
                 R"({"templates": {"x": {"gltf": "characters/NoSuchMan.glb"}}, "actors": []})", "/templates/x/gltf",
                 "does not exist"},
        BadScene{"regions that leave a block out",
                 R"({"town": {"tiles": "town/kenney_city_builder", "blocksX": 4, "blocksZ": 2, "regions": [{"from": [0, 0], "to": [2, 2]}, {"from": [2, 0], "to": [4, 1]}]},
                     "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/regions", "do not cover the town: block (2, 1)"},
        BadScene{"overlapping regions",
                 R"({"town": {"tiles": "town/kenney_city_builder", "blocksX": 2, "blocksZ": 2, "regions": [{"from": [0, 0], "to": [2, 2]}, {"from": [1, 1], "to": [2, 2]}]},
                     "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/regions/1", "overlaps region 0 at block (1, 1)"},
        BadScene{"a region beyond the town",
                 R"({"town": {"tiles": "town/kenney_city_builder", "blocksX": 2, "blocksZ": 2, "regions": [{"from": [0, 0], "to": [3, 2]}]},
                     "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/regions/0/to", "beyond the town's 2 x 2 blocks"},
        BadScene{"regions of no blocks",
                 R"({"town": {"tiles": "town/kenney_city_builder", "regions": {"size": [0, 2]}}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/regions/size", "at least one block"},
        BadScene{"missing tiles folder",
                 R"({"town": {"tiles": "town/nowhere"}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/tiles", "does not exist"},
        BadScene{"unknown procedural template", R"({"templates": {"x": {"procedural": "dragon"}}, "actors": []})",
                 "/templates/x/procedural", "not a procedural template"},
        BadScene{"template with both sources",
                 R"({"templates": {"x": {"procedural": "bird", "gltf": "characters/Fox.glb"}}, "actors": []})", "/templates/x",
                 "exactly one"},
        BadScene{"no templates", R"({"templates": {}, "actors": []})", "/templates", "at least one"},
        BadScene{"missing actors", R"({"templates": {"x": {"procedural": "bird"}}})", "/actors", "missing"},
        BadScene{"unknown top-level key", R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "weather": 1})",
                 "/weather", "not a known field"},
        BadScene{"walkers without a town",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [{"template": "x", "count": 1, "behaviour": "walk"}]})",
                 "/actors/0/behaviour", "needs a town"},
        BadScene{"town and walkways",
                 R"({"town": {"tiles": "town/kenney_city_builder"}, "walkways": {"floors": [{"center": [0, 0], "size": [4, 2]}]},
                     "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/walkways", "give 'town' or 'walkways', not both"},
        BadScene{"walkways without floors", R"({"walkways": {"floors": []}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/walkways/floors", "at least one floor"},
        BadScene{"walkway floor of no width",
                 R"({"walkways": {"floors": [{"center": [0, 0], "size": [0, 2]}]}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/walkways/floors/0/size/0", "must be above 0"},
        BadScene{"walkway cells too fine",
                 R"({"walkways": {"floors": [{"center": [0, 0], "size": [4, 2]}], "cellSize": 0.001}, "templates": {"x": {"procedural": "bird"}},
                     "actors": []})",
                 "/walkways/cellSize", "must be from 0.02 to 1 m, got 0.001"},
        BadScene{"walkers thinner than 0.1 m",
                 R"({"walkways": {"floors": [{"center": [0, 0], "size": [4, 2]}], "bodyRadius": 0.05}, "templates": {"x": {"procedural": "bird"}},
                     "actors": []})",
                 "/walkways/bodyRadius", "must be from 0.1 to 1 m, got 0.05"},
        BadScene{"unknown speed profile",
                 R"({"walkways": {"floors": [{"center": [0, 0], "size": [4, 2]}]}, "templates": {"x": {"procedural": "seed-humanoid"}},
                     "actors": [{"template": "x", "count": 1, "behaviour": "walk", "speedProfile": "rimea-toddlers"}]})",
                 "/actors/0/speedProfile", "'rimea-toddlers' is not a speed profile (rimea-under-30, rimea-30-to-50"},
        BadScene{"speed and speed profile",
                 R"({"walkways": {"floors": [{"center": [0, 0], "size": [4, 2]}]}, "templates": {"x": {"procedural": "seed-humanoid"}},
                     "actors": [{"template": "x", "count": 1, "behaviour": "walk", "speed": [1, 1.2], "speedProfile": "rimea-over-50"}]})",
                 "/actors/0/speedProfile", "give 'speed' or 'speedProfile', not both"},
        BadScene{"goal for standing people", scene(R"([{"template": "person", "count": 4, "behaviour": "idle", "goal": [0, 0]}])"),
                 "/actors/0/goal", "applies to walk only, not to 'idle'"},
        BadScene{"period without a goal",
                 R"({"walkways": {"floors": [{"center": [0, 0], "size": [4, 2]}]}, "templates": {"x": {"procedural": "seed-humanoid"}},
                     "actors": [{"template": "x", "count": 1, "behaviour": "walk", "period": [4, 0]}]})",
                 "/actors/0/period", "needs a 'goal' and walkways"},
        BadScene{"period too short",
                 R"({"walkways": {"floors": [{"center": [0, 0], "size": [4, 2]}]}, "templates": {"x": {"procedural": "seed-humanoid"}},
                     "actors": [{"template": "x", "count": 1, "behaviour": "walk", "goal": [1, 0], "period": [1, 0]}]})",
                 "/actors/0/period", "must be at least 2 m long"},
        BadScene{"goal beyond 100 km",
                 R"({"walkways": {"floors": [{"center": [0, 0], "size": [4, 2]}]}, "templates": {"x": {"procedural": "seed-humanoid"}},
                     "actors": [{"template": "x", "count": 1, "behaviour": "walk", "goal": [1e6, 0]}]})",
                 "/actors/0/goal/0", "must be from -100000 to 100000 m, got 1000000"},
        BadScene{"bad gaze type", scene(kActors, R"(, "effects": {"gaze": 3})"), "/effects/gaze", "must be an object"},
        BadScene{"avoidance quality out of range", scene(kActors, R"(, "effects": {"avoidance": {"quality": 4}})"),
                 "/effects/avoidance/quality", "must be from 0 to 3, got 4"},
        BadScene{"avoidance range under a radius", scene(kActors, R"(, "effects": {"avoidance": {"range": 0.5}})"),
                 "/effects/avoidance/range", "must be from 1 to 100 agent radii, got 0.5"},
        BadScene{"unknown avoidance model", scene(kActors, R"(, "effects": {"avoidance": {"model": "rvo"}})"),
                 "/effects/avoidance/model", "must be \"detour\" or \"orca\", got \"rvo\""},
        BadScene{"ORCA with DetourCrowd's quality", scene(kActors, R"(, "effects": {"avoidance": {"model": "orca", "quality": 2}})"),
                 "/effects/avoidance/quality", "ORCA has none"},
        BadScene{"unknown avoidance field", scene(kActors, R"(, "effects": {"avoidance": {"speed": 1}})"),
                 "/effects/avoidance/speed", "not a known field"},
        BadScene{"far update every step", scene(kActors, R"(, "effects": {"farUpdate": {"distance": 80, "every": 1}})"),
                 "/effects/farUpdate/every", "from 2 to 1000"},
        BadScene{"far update without distance", scene(kActors, R"(, "effects": {"farUpdate": {"every": 4}})"),
                 "/effects/farUpdate/distance", "is missing"},
        BadScene{"camera times not increasing",
                 scene(kActors, R"(, "camera": {"path": [{"time": 1, "eye": [0, 1, 0], "target": [1, 0, 0]}, {"time": 1, "eye": [0, 1, 0], "target": [1, 0, 0]}]})"),
                 "/camera/path/1/time", "must increase"},
        BadScene{"hysteresis out of range", scene(kActors, R"(, "representation": {"hysteresis": 0.9})"),
                 "/representation/hysteresis", "must be from 0 to 0.5, got 0.9"},
        BadScene{"negative scale", R"({"templates": {"x": {"gltf": "characters/Fox.glb", "scale": -0.01}}, "actors": []})",
                 "/templates/x/scale", "must be from 0.0001 to 1000, got -0.01"},
        BadScene{"scale on a procedural template", R"({"templates": {"x": {"procedural": "bird", "scale": 2}}, "actors": []})",
                 "/templates/x", "glTF templates only"},
        BadScene{"joint angle too wide", R"({"templates": {"x": {"gltf": "characters/Fox.glb", "jointMinAngle": 0.5}}, "actors": []})",
                 "/templates/x/jointMinAngle", "must be from 0, below 0.1 radians"},
        BadScene{"lod distances not increasing",
                 R"({"templates": {"x": {"gltf": "characters/Fox.glb", "lod": [{"until": 30}, {"until": 20}]}}, "actors": []})",
                 "/templates/x/lod/1/until", "must exceed"},
        BadScene{"lod share above 1",
                 R"({"templates": {"x": {"gltf": "characters/Fox.glb", "lod": [{"until": 30, "triangles": 1.5}]}}, "actors": []})",
                 "/templates/x/lod/0/triangles", "must be above 0, up to 1, got 1.5"},
        BadScene{"open-ended lod level before the last",
                 R"({"templates": {"x": {"gltf": "characters/Fox.glb", "lod": [{"triangles": 1}, {"until": 20}]}}, "actors": []})",
                 "/templates/x/lod/0", "needs 'until'"},
        BadScene{"town lod distances not increasing",
                 R"({"town": {"tiles": "town/kenney_city_builder", "lod": [{"until": 60}, {"until": 60, "triangles": 0.5}]},
                     "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/lod/1/until", "must exceed"},
        BadScene{"town lod share not positive",
                 R"({"town": {"tiles": "town/kenney_city_builder", "lod": [{"until": 60}, {"triangles": 0}]},
                     "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/lod/1/triangles", "must be above 0, up to 1, got 0"},
        BadScene{"town lod not an array",
                 R"({"town": {"tiles": "town/kenney_city_builder", "lod": 50}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/lod", "must be an array"},
        BadScene{"town lod without levels",
                 R"({"town": {"tiles": "town/kenney_city_builder", "lod": []}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/lod", "at least one level"},
        BadScene{"town lod scale without levels",
                 R"({"town": {"tiles": "town/kenney_city_builder", "lodScale": 0.5}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/lodScale", "needs the town's 'lod' levels"},
        BadScene{"town lod scale not positive",
                 R"({"town": {"tiles": "town/kenney_city_builder", "lod": [{"until": 60}, {"triangles": 0.5}], "lodScale": 0},
                     "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/lodScale", "must be from 0.0001 to 10000, got 0"},
        BadScene{"occluders not a boolean",
                 R"({"town": {"tiles": "town/kenney_city_builder", "occluders": 1}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/occluders", "true or false"},
        BadScene{"occlusion buffer too small",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"occlusion": {"width": 4}}})",
                 "/representation/occlusion/width", "must be from 8 to 4096 pixels, got 4"},
        BadScene{"occlusion buffer too large",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"occlusion": {"height": 5000}}})",
                 "/representation/occlusion/height", "must be from 8 to 4096 pixels, got 5000"},
        BadScene{"no occluder allowed",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"occlusion": {"maxOccluders": 0}}})",
                 "/representation/occlusion/maxOccluders", "must be from 1 to 1000000, got 0"},
        BadScene{"occlusion rest without frames",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"occlusion": {"rest": {"below": 0.1}}}})",
                 "/representation/occlusion/rest/frames", "is missing"},
        BadScene{"occlusion rest share above one",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"occlusion": {"rest": {"frames": 4, "below": 1.5}}}})",
                 "/representation/occlusion/rest/below", "must be from 0 to 1, got 1.5"},
        BadScene{"occlusion rest wake angle too wide",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"occlusion": {"rest": {"frames": 4, "wakeAngle": 200}}}})",
                 "/representation/occlusion/rest/wakeAngle", "must be from 0 to 180 degrees, got 200"},
        BadScene{"unknown occlusion field",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"occlusion": {"depth": 3}}})",
                 "/representation/occlusion/depth", "not a known field"},
        BadScene{"key-pose cache of an unknown template",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"keyPoseCache": {"rows": {"y": 8}}}})",
                 "/representation/keyPoseCache/rows/y", "no declared template"},
        BadScene{"key-pose cache without rows",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"keyPoseCache": {"rows": {}}}})",
                 "/representation/keyPoseCache/rows", "at least one template"},
        BadScene{"key-pose cache of no row",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"keyPoseCache": {"rows": {"x": 0}}}})",
                 "/representation/keyPoseCache/rows/x", "must be from 1 to 65535 rows, got 0"},
        BadScene{"key-pose cache mode unknown",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"keyPoseCache": {"mode": "lazy", "rows": {"x": 8}}}})",
                 "/representation/keyPoseCache/mode", "intermittent"},
        BadScene{"impostor views unknown",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"impostorViews": "morphed"}})",
                 "/representation/impostorViews", "must be \"blend\", \"nearest\" or \"warped\", got \"morphed\""},
        BadScene{"impostor atlas unknown",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"impostorAtlas": "quarter"}})",
                 "/representation/impostorAtlas", "must be \"full\", \"half-keyframes\" or \"half\", got \"quarter\""},
        BadScene{"impostor atlas not a string",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"impostorAtlas": 2}})",
                 "/representation/impostorAtlas", "must be a string"},
        BadScene{"impostor smoothstep not a boolean",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"impostorSmoothstep": 1}})",
                 "/representation/impostorSmoothstep", "must be true or false"},
        BadScene{"impostor smoothstep of the nearest view",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"impostorViews": "nearest", "impostorSmoothstep": true}})",
                 "/representation/impostorSmoothstep", "applies to \"blend\" and \"warped\" only"},
        BadScene{"key-pose band beyond the impostors",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"impostorDistance": 30, "keyPoseCache": {"distance": 40, "rows": {"x": 8}}}})",
                 "/representation/keyPoseCache/distance", "below impostorDistance"},
        BadScene{"key-pose rate negative",
                 R"({"templates": {"x": {"procedural": "bird"}}, "actors": [], "representation": {"keyPoseCache": {"keyPosesPerSecond": -1, "rows": {"x": 8}}}})",
                 "/representation/keyPoseCache/keyPosesPerSecond", "must be above 0, up to 1000, got -1"},
        // The document itself.
        BadScene{"empty document", "", "", "is empty"},
        BadScene{"document of spaces", " \n\t ", "", "is empty"},
        BadScene{"truncated document", scene(kActors).substr(0, 120), "", "is not valid JSON (line 5"},
        BadScene{"nested 100000 deep", std::string(100000, '[') + std::string(100000, ']'), "", "must be an object, got array"},
        BadScene{"document of 17 MiB", R"({"name": ")" + std::string(17u << 20, 'x') + R"("})", "", "is larger than 16 MiB"},
        BadScene{"number beyond a double", R"({"step": 1e400, "templates": {"x": {"procedural": "bird"}}, "actors": []})", "",
                 "holds a number beyond a double's range: 1e400"},
        BadScene{"integer beyond 64 bits", R"({"seed": 100000000000000000000000000000, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/seed", "must be an integer"},
        BadScene{"step too long", R"({"step": 2, "templates": {"x": {"procedural": "bird"}}, "actors": []})", "/step",
                 "must be above 0, up to 0.5 s, got 2"},
        // Files that are not what the key asks for.
        BadScene{"tiles naming a file",
                 R"({"town": {"tiles": "town/kenney_city_builder/pavement.glb"}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/tiles", "is a file, not a folder"},
        BadScene{"gltf naming a folder", R"({"templates": {"x": {"gltf": "characters"}}, "actors": []})", "/templates/x/gltf",
                 "is a folder, not a glTF file"},
        BadScene{"gltf naming a folder called .glb", R"({"templates": {"x": {"gltf": "folder.glb"}}, "actors": []})", "/templates/x/gltf",
                 "is a folder, not a glTF file", true},
        BadScene{"gltf of 0 bytes", R"({"templates": {"x": {"gltf": "empty.glb"}}, "actors": []})", "/templates/x/gltf", "is empty", true},
        BadScene{"gltf that is text", R"({"templates": {"x": {"gltf": "text.glb"}}, "actors": []})", "/templates/x/gltf",
                 "is not a glTF file", true},
        // Physical bounds, at the key that holds the value.
        BadScene{"tile of 1e300 m",
                 R"({"town": {"tiles": "town/kenney_city_builder", "tileSize": 1e300}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/tileSize", "must be from 1 to 100 m, got 1e+300"},
        BadScene{"a million blocks across",
                 R"({"town": {"tiles": "town/kenney_city_builder", "blocksX": 1000000}, "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/town/blocksX", "must be from 1 to 1000 blocks, got 1000000"},
        BadScene{"template scale of 1e300", R"({"templates": {"x": {"gltf": "characters/Fox.glb", "scale": 1e300}}, "actors": []})",
                 "/templates/x/scale", "must be from 0.0001 to 1000, got 1e+300"},
        BadScene{"walk clip authored at 1e6 m/s", birds(R"(, "walkClipSpeed": 1e6)"), "/templates/x/walkClipSpeed",
                 "must be from 0.05 to 20 m/s"},
        BadScene{"walkers at 1e6 m/s", scene(R"([{"template": "cesium", "count": 5, "behaviour": "walk", "speed": [1, 1e6]}])"),
                 "/actors/0/speed/1", "must be from 0.1 to 10 m/s, got 1000000"},
        BadScene{"a flock at 1000 m/s", birds("", R"([{"template": "x", "count": 5, "behaviour": "flight", "speed": [1000, 1000]}])"),
                 "/actors/0/speed/0", "must be from 0.5 to 50 m/s"},
        BadScene{"a flock at 1e6 m", birds("", R"([{"template": "x", "count": 5, "behaviour": "flight", "altitude": [10, 1e6]}])"),
                 "/actors/0/altitude/1", "must be from 0.5 to 2000 m"},
        BadScene{"an area 1e9 m away", birds("", R"([{"template": "x", "count": 5, "behaviour": "idle", "area": {"center": [1e9, 0]}}])"),
                 "/actors/0/area/center/0", "must be from -100000 to 100000 m"},
        BadScene{"an area of no size", birds("", R"([{"template": "x", "count": 5, "behaviour": "idle", "area": {"size": [10, 0]}}])"),
                 "/actors/0/area/size/1", "must be above 0, up to 100000 m"},
        BadScene{"a priority of 1e9", birds("", R"([{"template": "x", "count": 5, "behaviour": "idle", "priority": 1e9}])"),
                 "/actors/0/priority", "must be above 0, up to 1000"},
        BadScene{"groups of 1e9 people",
                 birds("", R"([{"template": "x", "count": 10, "behaviour": "idle", "groupSize": [1000000000, 1000000000]}])"),
                 "/actors/0/groupSize/0", "must be from 1 to 1000 people"},
        BadScene{"groups larger than the count", birds("", R"([{"template": "x", "count": 4, "behaviour": "idle", "groupSize": [3, 5]}])"),
                 "/actors/0/groupSize", "the largest group (5) is larger than 'count' (4)"},
        BadScene{"group sizes not whole", birds("", R"([{"template": "x", "count": 40, "behaviour": "idle", "groupSize": [3, 4.5]}])"),
                 "/actors/0/groupSize/1", "must be an integer"},
        BadScene{"speed of a standing group", birds("", R"([{"template": "x", "count": 5, "behaviour": "idle", "speed": [1, 2]}])"),
                 "/actors/0/speed", "applies to walk and flight only, not to 'idle'"},
        BadScene{"altitude of walkers", scene(R"([{"template": "cesium", "count": 5, "behaviour": "walk", "altitude": [1, 2]}])"),
                 "/actors/0/altitude", "applies to flight only, not to 'walk'"},
        BadScene{"group size of a flock", birds("", R"([{"template": "x", "count": 5, "behaviour": "flight", "groupSize": [1, 2]}])"),
                 "/actors/0/groupSize", "applies to idle only, not to 'flight'"},
        BadScene{"no behavioural levels", scene(R"([{"template": "cesium", "count": 5, "behaviour": "walk", "levels": []}])"),
                 "/actors/0/levels", "at least one distance"},
        BadScene{"behavioural level 1e9 m", scene(R"([{"template": "cesium", "count": 5, "behaviour": "walk", "levels": [10, 1e9]}])"),
                 "/actors/0/levels/1", "must be above 0, up to 100000 m"},
        BadScene{"no gaze levels", scene(kActors, R"(, "effects": {"gaze": {"levels": []}})"), "/effects/gaze/levels",
                 "at least one distance"},
        BadScene{"gaze across a town", scene(kActors, R"(, "effects": {"gaze": {"range": 5000}})"), "/effects/gaze/range",
                 "must be above 0, up to 1000 m"},
        BadScene{"face levels decreasing", scene(kActors, R"(, "effects": {"face": {"levels": [20, 10]}})"), "/effects/face/levels/1",
                 "level ends must increase"},
        BadScene{"an expression without a name", scene(kActors, R"(, "effects": {"face": {"expressions": [{"duration": 2}]}})"),
                 "/effects/face/expressions/0/name", "is missing"},
        BadScene{"two expressions of one name",
                 scene(kActors, R"(, "effects": {"face": {"expressions": [{"name": "a"}, {"name": "a"}]}})"),
                 "/effects/face/expressions/1/name", "already an expression"},
        BadScene{"an expression weight of 2",
                 scene(kActors, R"(, "effects": {"face": {"expressions": [{"name": "a", "weights": {"Angry": 2}}]}})"),
                 "/effects/face/expressions/0/weights/Angry", "must be from -1 to 1"},
        BadScene{"an expression held 0 s", scene(kActors, R"(, "effects": {"face": {"expressions": [{"name": "a", "duration": 0}]}})"),
                 "/effects/face/expressions/0/duration", "must be above 0, up to 3600 s"},
        BadScene{"no expressions", scene(kActors, R"(, "effects": {"face": {"expressions": []}})"), "/effects/face/expressions",
                 "at least one expression"},
        BadScene{"an unknown face key", scene(kActors, R"(, "effects": {"face": {"smile": 1}})"), "/effects/face/smile",
                 "is not a known field"},
        BadScene{"a blink spread over its mean", scene(kActors, R"(, "effects": {"blink": {"mean": 2, "spread": 3}})"),
                 "/effects/blink/spread", "below the mean"},
        BadScene{"a blink longer than its intervals", scene(kActors, R"(, "effects": {"blink": {"mean": 1, "spread": 0.9, "duration": 0.5}})"),
                 "/effects/blink/duration", "shorter than the shortest interval"},
        BadScene{"no phrases", scene(kActors, R"(, "effects": {"phrase": {"phrases": []}})"), "/effects/phrase/phrases",
                 "at least one phrase"},
        BadScene{"an empty phrase", scene(kActors, R"(, "effects": {"phrase": {"phrases": [""]}})"), "/effects/phrase/phrases/0",
                 "must not be empty"},
        BadScene{"phrases in groups of 0", scene(kActors, R"(, "effects": {"phrase": {"groupSize": 0}})"), "/effects/phrase/groupSize",
                 "must be from 1 to 1000"},
        BadScene{"phrase as a number", scene(kActors, R"(, "effects": {"phrase": 3})"), "/effects/phrase", "must be an object"},
        BadScene{"far update at 1e9 m", scene(kActors, R"(, "effects": {"farUpdate": {"distance": 1e9, "every": 4}})"),
                 "/effects/farUpdate/distance", "must be above 0, up to 100000 m"},
        BadScene{"impostors from 1e9 m", scene(kActors, R"(, "representation": {"impostorDistance": 1e9})"),
                 "/representation/impostorDistance", "must be from 0 to 100000 m"},
        BadScene{"LOD scale of 1e9", scene(kActors, R"(, "representation": {"lodScale": 1e9})"), "/representation/lodScale",
                 "must be from 0.0001 to 10000"},
        BadScene{"occlusion waking after 1e9 m",
                 birds("", R"([], "representation": {"occlusion": {"rest": {"frames": 4, "wakeDistance": 1e9}}})"),
                 "/representation/occlusion/rest/wakeDistance", "must be from 0 to 1000000 m"},
        BadScene{"key-pose band from 1e9 m", birds("", R"([], "representation": {"keyPoseCache": {"distance": 1e9, "rows": {"x": 8}}})"),
                 "/representation/keyPoseCache/distance", "must be above 0, up to 100000 m"},
        BadScene{"field of view of 180 degrees", scene(kActors, R"(, "camera": {"fov": 180})"), "/camera/fov",
                 "must be above 0, below 180 degrees"},
        BadScene{"near plane at 0", scene(kActors, R"(, "camera": {"near": 0})"), "/camera/near", "must be above 0, up to 1000 m"},
        BadScene{"far plane at 1e12 m", scene(kActors, R"(, "camera": {"far": 1e12})"), "/camera/far", "must be above 0, up to 10000000 m"},
        BadScene{"camera path time -5",
                 scene(kActors, R"(, "camera": {"path": [{"time": -5, "eye": [0, 1, 0], "target": [1, 0, 0]}]})"),
                 "/camera/path/0/time", "must be from 0 to 1000000 s, got -5"},
        BadScene{"camera eye 1e300 m away",
                 scene(kActors, R"(, "camera": {"path": [{"time": 0, "eye": [0, 1e300, 0], "target": [1, 0, 0]}]})"),
                 "/camera/path/0/eye/1", "must be from -1000000 to 1000000 m"},
        BadScene{"empty camera path", scene(kActors, R"(, "camera": {"path": []})"), "/camera/path", "at least one key"},
        // Names.
        BadScene{"two groups of one name",
                 scene(R"([{"name": "a", "template": "cesium", "count": 5, "behaviour": "walk"}, {"name": "a", "template": "person", "count": 5, "behaviour": "idle"}])"),
                 "/actors/1/name", "repeats the name of /actors/0 ('a')"},
        BadScene{"a name taken from a default name",
                 scene(R"([{"template": "cesium", "count": 5, "behaviour": "walk"}, {"name": "group 0", "template": "person", "count": 5, "behaviour": "idle"}])"),
                 "/actors/1/name", "repeats the name of /actors/0"},
        BadScene{"a group name holding NUL", scene(R"([{"name": "a\u0000b", "template": "cesium", "count": 5, "behaviour": "walk"}])"),
                 "/actors/0/name", "control characters (found byte 0)"},
        BadScene{"an empty group name", scene(R"([{"name": "", "template": "cesium", "count": 5, "behaviour": "walk"}])"),
                 "/actors/0/name", "must not be empty"},
        BadScene{"a scene name holding a newline", R"({"name": "two\nlines", "templates": {"x": {"procedural": "bird"}}, "actors": []})",
                 "/name", "control characters (found byte 10)"},
        BadScene{"a template name holding NUL", R"({"templates": {"x\u0000": {"procedural": "bird"}}, "actors": []})",
                 std::string("/templates/x\0", 13), "control characters"}),
    [](const auto& param) {
        std::string name = param.param.what;
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        return name;
    });

TEST(SceneParser, AvoidanceQualityAndRangeAreRead) {
    const SceneDescription plain = parseScene(scene(kActors, R"(, "effects": {"avoidance": true})"), kAssets);
    EXPECT_TRUE(plain.effects.avoidance);
    EXPECT_EQ(plain.effects.avoidanceQuality, 3);
    EXPECT_DOUBLE_EQ(plain.effects.avoidanceRange, 12.0);
    const SceneDescription coarse = parseScene(scene(kActors, R"(, "effects": {"avoidance": {"quality": 1, "range": 6}})"), kAssets);
    EXPECT_TRUE(coarse.effects.avoidance);
    EXPECT_EQ(coarse.effects.avoidanceQuality, 1);
    EXPECT_DOUBLE_EQ(coarse.effects.avoidanceRange, 6.0);
    EXPECT_EQ(coarse.effects.avoidanceModel, "detour");
    const SceneDescription orca = parseScene(scene(kActors, R"(, "effects": {"avoidance": {"model": "orca"}})"), kAssets);
    EXPECT_TRUE(orca.effects.avoidance);
    EXPECT_EQ(orca.effects.avoidanceModel, "orca");
}

TEST(SceneParser, FarUpdateIsReadOnlyWhenDeclared) {
    EXPECT_EQ(parseScene(scene(kActors), kAssets).effects.farUpdateEvery, 1);
    const SceneDescription far = parseScene(scene(kActors, R"(, "effects": {"farUpdate": {"distance": 80, "every": 4}})"), kAssets);
    EXPECT_DOUBLE_EQ(far.effects.farUpdateDistance, 80.0);
    EXPECT_EQ(far.effects.farUpdateEvery, 4);
}

TEST(SceneParser, OcclusionIsReadOnlyWhenDeclared) {
    EXPECT_FALSE(parseScene(scene(kActors), kAssets).representation.occlusion.has_value());
    EXPECT_FALSE(parseScene(scene(kActors), kAssets).town->occluders);
    std::string text = scene(kActors, R"(, "representation": {"occlusion": {"width": 320, "height": 180, "maxOccluders": 40}})");
    const std::string tiles = R"("tiles": "town/kenney_city_builder")";
    text.replace(text.find(tiles), tiles.size(), tiles + R"(, "occluders": true)");
    const SceneDescription s = parseScene(text, kAssets);
    ASSERT_TRUE(s.representation.occlusion.has_value());
    EXPECT_EQ(s.representation.occlusion->width, 320);
    EXPECT_EQ(s.representation.occlusion->height, 180);
    EXPECT_EQ(s.representation.occlusion->maxOccluders, 40);
    EXPECT_EQ(s.representation.occlusion->restFrames, 0) << "occlusion never rests unless the scene says so";
    EXPECT_TRUE(s.town->occluders);
    const SceneDescription resting = parseScene(
        scene(kActors, R"(, "representation": {"occlusion": {"rest": {"frames": 8, "below": 0.2, "wakeDistance": 3, "wakeAngle": 15}}})"),
        kAssets);
    EXPECT_EQ(resting.representation.occlusion->restFrames, 8);
    EXPECT_DOUBLE_EQ(resting.representation.occlusion->restBelow, 0.2);
    EXPECT_DOUBLE_EQ(resting.representation.occlusion->wakeDistance, 3.0);
    EXPECT_DOUBLE_EQ(resting.representation.occlusion->wakeAngleDegrees, 15.0);
}

TEST(SceneParser, KeyPoseCachesAreReadOnlyWhenDeclared) {
    EXPECT_FALSE(parseScene(scene(kActors), kAssets).representation.keyPoseCache.has_value());
    const std::string text = scene(kActors, R"(, "representation": {"keyPoseCache": {"distance": 12, "mode": "interpolative",
        "keyPosesPerSecond": 10, "rows": {"cesium": 48}}})");
    const SceneDescription s = parseScene(text, kAssets);
    ASSERT_TRUE(s.representation.keyPoseCache.has_value());
    EXPECT_EQ(s.representation.keyPoseCache->distance, 12.0);
    EXPECT_EQ(s.representation.keyPoseCache->mode, throng::KeyPoseMode::Interpolative);
    EXPECT_EQ(s.representation.keyPoseCache->keyPosesPerSecond, 10.0);
    EXPECT_EQ(s.representation.keyPoseCache->rows.at("cesium"), 48u);
}

TEST(SceneParser, ImpostorViewChoiceDefaultsToTheSmoothlessBlend) {
    const SceneDescription plain = parseScene(scene(kActors), kAssets);
    EXPECT_EQ(plain.representation.impostorViews, ImpostorViews::Blend);
    EXPECT_FALSE(plain.representation.impostorSmoothstep);
    const SceneDescription sharp = parseScene(scene(kActors, R"(, "representation": {"impostorSmoothstep": true})"), kAssets);
    EXPECT_EQ(sharp.representation.impostorViews, ImpostorViews::Blend);
    EXPECT_TRUE(sharp.representation.impostorSmoothstep);
    const SceneDescription snap = parseScene(scene(kActors, R"(, "representation": {"impostorViews": "nearest"})"), kAssets);
    EXPECT_EQ(snap.representation.impostorViews, ImpostorViews::Nearest);
    EXPECT_EQ(parseScene(scene(kActors, R"(, "representation": {"impostorViews": "warped", "impostorSmoothstep": true})"), kAssets)
                  .representation.impostorViews,
              ImpostorViews::Warped);
    EXPECT_EQ(plain.representation.impostorAtlas, ImpostorAtlasStorage::HalfKeyframes);
    EXPECT_EQ(parseScene(scene(kActors, R"(, "representation": {"impostorAtlas": "half"})"), kAssets).representation.impostorAtlas,
              ImpostorAtlasStorage::Half);
    EXPECT_EQ(parseScene(scene(kActors, R"(, "representation": {"impostorAtlas": "full"})"), kAssets).representation.impostorAtlas,
              ImpostorAtlasStorage::Full);
}

TEST(SceneParser, AMissingFileIsAnError) { EXPECT_THROW(parseSceneFile("/nonexistent/scene.json"), SceneError); }

namespace {

// The repository's root, from where the default scene lies (apps/town/scenes/default.json).
std::filesystem::path repositoryRoot() { return std::filesystem::path(throng::testkit::townDefaultScene()).parent_path() / "../../.."; }

}  // namespace

TEST(SceneParser, EveryShippedSceneParses) {
    const std::filesystem::path root = repositoryRoot();
    for (const char* file : {"apps/town/scenes/default.json", "tests/town/scenes/plain.json", "tests/town/scenes/effects.json",
                             "tests/oracles/scenes/occlusion.json"}) {
        SCOPED_TRACE(file);
        EXPECT_NO_THROW(parseSceneFile((root / file).string()));
    }
}

// Every range the parser checks is the one the scene guide states, in the row of its key in the
// table of its section ("## `town`", "### LOD levels", ...).
TEST(SceneParser, LooksAreGeneratedOrRead) {
    const SceneDescription d = parseScene(
        R"({"templates": {"a": {"gltf": "characters/CesiumMan.glb", "looks": 12},
                          "b": {"gltf": "characters/CesiumMan.glb", "looks": [{"skin": "#FFCC99", "hair": "#101010", "top": "#2050a0", "bottom": "#000000"}]},
                          "c": {"gltf": "characters/CesiumMan.glb"}}, "actors": []})",
        kAssets);
    ASSERT_EQ(d.templates.at("a").looks.size(), 12u);
    const std::set<std::array<std::uint32_t, 4>> distinct = [&] {
        std::set<std::array<std::uint32_t, 4>> s;
        for (const throng::BodyLook& l : d.templates.at("a").looks) s.insert(l.rgba);
        return s;
    }();
    EXPECT_EQ(distinct.size(), 12u);
    ASSERT_EQ(d.templates.at("b").looks.size(), 1u);
    EXPECT_EQ(d.templates.at("b").looks[0].rgba[0], throng::packBodyColour(0xff, 0xcc, 0x99));
    EXPECT_EQ(d.templates.at("b").looks[0].rgba[2], throng::packBodyColour(0x20, 0x50, 0xa0));
    EXPECT_TRUE(d.templates.at("c").looks.empty());
    // All 240 generated looks differ; actors of a group spread over them.
    std::set<std::array<std::uint32_t, 4>> all;
    for (const throng::BodyLook& l : generatedLooks(240)) all.insert(l.rgba);
    EXPECT_EQ(all.size(), 240u);
    const std::vector<throng::BodyLook> eight = generatedLooks(8);
    std::set<std::array<std::uint32_t, 4>> worn;
    for (std::size_t i = 0; i < 40; ++i) worn.insert(lookForActor(eight, 0, i).rgba);
    EXPECT_EQ(worn.size(), 8u) << "40 actors should wear all 8 looks";
}

// The default scene dresses every glTF template with a skinned body in at least four looks (issue
// 37's diversity). RobotExpressive's body is rigid parts, which carry no body regions to recolour.
TEST(SceneParser, TheDefaultSceneHasFourLooksPerCharacter) {
    const SceneDescription d = parseSceneFile((repositoryRoot() / "apps/town/scenes/default.json").string());
    for (const auto& [name, t] : d.templates) {
        if (t.gltf.empty() || t.gltf.find("RobotExpressive") != std::string::npos) continue;
        std::set<std::array<std::uint32_t, 4>> distinct;
        for (const throng::BodyLook& l : t.looks) distinct.insert(l.rgba);
        EXPECT_GE(distinct.size(), 4u) << name;
    }
}

// Faces: the three effects declared with their settings, `true` giving the defaults, and none by default.
TEST(SceneParser, FacesAreDeclaredEffectByEffect) {
    const SceneDescription none = parseScene(scene(kActors), kAssets);
    EXPECT_FALSE(none.effects.faces.face || none.effects.faces.blink || none.effects.faces.phrase);
    const SceneDescription all = parseScene(scene(kActors, R"(, "effects": {
        "face": {"levels": [10, 20], "transition": 0.3, "expressions": [{"name": "calm"}, {"name": "cross", "duration": 2, "weights": {"Angry": 0.9}}]},
        "blink": {"levels": [8], "mean": 3, "spread": 1, "duration": 0.2},
        "phrase": {"levels": [9], "phrases": ["Hi"], "lettersPerSecond": 10, "pause": 2, "groupSize": 4, "mouthTargets": ["Surprised"]}})"),
                                            kAssets);
    const auto& f = all.effects.faces;
    EXPECT_TRUE(f.face && f.blink && f.phrase);
    EXPECT_EQ(f.faceLevels, (std::vector<double>{10, 20}));
    EXPECT_DOUBLE_EQ(f.transition, 0.3);
    ASSERT_EQ(f.expressions.size(), 2u);
    EXPECT_EQ(f.expressions[1].name, "cross");
    EXPECT_DOUBLE_EQ(f.expressions[1].duration, 2.0);
    EXPECT_FLOAT_EQ(f.expressions[1].weights.at("Angry"), 0.9f);
    EXPECT_TRUE(f.expressions[0].weights.empty());
    EXPECT_DOUBLE_EQ(f.blinkMean, 3.0);
    EXPECT_DOUBLE_EQ(f.blinkDuration, 0.2);
    EXPECT_EQ(f.phrases, (std::vector<std::string>{"Hi"}));
    EXPECT_EQ(all.effects.phraseGroupSize, 4);
    EXPECT_EQ(f.mouthTargets, (std::vector<std::string>{"Surprised"}));
    const SceneDescription defaults = parseScene(scene(kActors, R"(, "effects": {"face": true, "blink": false, "phrase": true})"), kAssets);
    EXPECT_TRUE(defaults.effects.faces.face);
    EXPECT_FALSE(defaults.effects.faces.blink);
    EXPECT_TRUE(defaults.effects.faces.expressions.empty()) << "true: the character's own targets";
    EXPECT_FALSE(defaults.effects.faces.phrases.empty()) << "true: stock phrases";
}

// The default scene gives RobotExpressive characters all three face effects (issue 38).
TEST(SceneParser, TheDefaultSceneDeclaresFaces) {
    const SceneDescription d = parseSceneFile((repositoryRoot() / "apps/town/scenes/default.json").string());
    EXPECT_TRUE(d.effects.faces.face && d.effects.faces.blink && d.effects.faces.phrase);
    bool expressive = false;
    for (const auto& g : d.actors) expressive = expressive || g.templateName == "expressive";
    EXPECT_TRUE(expressive);
}

TEST(SceneParser, TheSceneGuideStatesEveryRange) {
    std::ifstream in(repositoryRoot() / "docs/guides/scene-files.md");
    ASSERT_TRUE(in) << "docs/guides/scene-files.md";
    std::vector<std::pair<std::string, std::string>> rows;  // {section, row}
    std::string line, section;
    while (std::getline(in, line)) {
        if (line.rfind("#", 0) == 0) {
            section = line.substr(line.find_first_not_of('#'));
            std::erase(section, '`');
            section = section.substr(section.find_first_not_of(' '));
            if (section.rfind("The ", 0) == 0) section = section.substr(4);
            for (char& c : section) c = char(std::tolower(static_cast<unsigned char>(c)));
        } else if (line.rfind("| `", 0) == 0) {
            rows.emplace_back(section, line);
        }
    }
    for (const SceneRange& r : sceneRanges()) {
        std::string key = r.key;
        if (const auto paren = key.find(" ("); paren != std::string::npos) key.resize(paren);
        std::string heading = r.section;
        for (char& c : heading) c = char(std::tolower(static_cast<unsigned char>(c)));
        const std::string start = "| `" + key + "` |", range = describeRange(r);
        bool found = false, stated = false;
        for (const auto& [s, row] : rows)
            if (s == heading && row.rfind(start, 0) == 0) found = true, stated = stated || row.find(range) != std::string::npos;
        EXPECT_TRUE(found) << "no row " << start << " under the heading '" << r.section << "'";
        EXPECT_TRUE(!found || stated) << "the row of " << r.section << " / " << r.key << " does not say '" << range << "'";
    }
}
