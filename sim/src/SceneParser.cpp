#include "throng/sim/SceneParser.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <fstream>
#include <initializer_list>
#include <map>
#include <algorithm>
#include <string_view>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include <glm/geometric.hpp>

#include "throng/sim/CrowdLooks.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneError.h"
#include "throng/sim/SceneRanges.h"
#include "throng/sim/SpeedProfile.h"
#include "throng/sim/TownRegions.h"

namespace throng::sim {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Reads values at a JSON path, turning every problem into a SceneError naming the path.
class Reader {
public:
    Reader(const json& value, std::string path, const std::string& file) : v_(value), path_(std::move(path)), file_(file) {}

    [[noreturn]] void fail(const std::string& reason) const { throw SceneError(file_, path_, reason); }
    const std::string& path() const { return path_; }
    const json& value() const { return v_; }
    bool has(const char* key) const { return v_.contains(key); }

    Reader at(const char* key) const {
        if (!v_.contains(key)) Reader(v_, path_ + "/" + key, file_).fail("is missing");
        return Reader(v_.at(key), path_ + "/" + key, file_);
    }
    Reader at(std::size_t i) const { return Reader(v_.at(i), path_ + "/" + std::to_string(i), file_); }

    // Must be an object (of any keys).
    void anyObject() const {
        if (!v_.is_object()) fail("must be an object, got " + typeName());
    }
    // Must be an object whose keys are all in `allowed`.
    void object(std::initializer_list<const char*> allowed) const {
        anyObject();
        const std::set<std::string> keys(allowed.begin(), allowed.end());
        for (auto it = v_.begin(); it != v_.end(); ++it)
            if (!keys.count(it.key())) Reader(it.value(), path_ + "/" + it.key(), file_).fail("is not a known field");
    }
    std::size_t array() const {
        if (!v_.is_array()) fail("must be an array, got " + typeName());
        return v_.size();
    }
    double number() const {
        if (!v_.is_number()) fail("must be a number, got " + typeName());
        const double d = v_.get<double>();
        if (!std::isfinite(d)) fail("must be finite");
        return d;
    }
    double positive() const {
        const double d = number();
        if (!(d > 0.0)) fail("must be positive, got " + fmt(d));
        return d;
    }
    std::int64_t integer() const {
        if (!v_.is_number_integer()) fail("must be an integer, got " + typeName());
        return v_.get<std::int64_t>();
    }
    std::int64_t atLeast(std::int64_t lo) const {
        const std::int64_t i = integer();
        if (i < lo) fail("must be at least " + std::to_string(lo) + ", got " + std::to_string(i));
        return i;
    }
    bool boolean() const {
        if (!v_.is_boolean()) fail("must be true or false, got " + typeName());
        return v_.get<bool>();
    }
    std::string string() const {
        if (!v_.is_string()) fail("must be a string, got " + typeName());
        return v_.get<std::string>();
    }
    template <int N>
    glm::vec<N, double> vec() const {
        if (array() != N) fail("must be an array of " + std::to_string(N) + " numbers");
        glm::vec<N, double> out;
        for (int i = 0; i < N; ++i) out[i] = at(std::size_t(i)).number();
        return out;
    }
    // A [min, max] range with 0 < min <= max.
    glm::dvec2 range() const {
        const glm::dvec2 r = vec<2>();
        if (!(r.x > 0.0) || r.y < r.x) fail("must be [min, max] with 0 < min <= max");
        return r;
    }
    // A number within the scene guide's range for `key` of table `section` (SceneRanges.h).
    double within(const char* section, const char* key) const {
        const SceneRange& r = sceneRange(section, key);
        const double d = r.whole ? double(integer()) : number();
        if (!inRange(r, d)) fail("must be " + describeRange(r) + unitOf(r) + ", got " + fmt(d));
        return d;
    }
    // An integer within its range.
    std::int64_t wholeWithin(const char* section, const char* key) const { return std::int64_t(within(section, key)); }
    // N numbers, each within the range of `key`.
    template <int N>
    glm::vec<N, double> vecWithin(const char* section, const char* key) const {
        if (array() != N) fail("must be an array of " + std::to_string(N) + " numbers");
        glm::vec<N, double> out;
        for (int i = 0; i < N; ++i) out[i] = at(std::size_t(i)).within(section, key);
        return out;
    }
    // [min, max], both within the range of `key`, min <= max.
    glm::dvec2 rangeWithin(const char* section, const char* key) const {
        const glm::dvec2 r = vecWithin<2>(section, key);
        if (r.y < r.x) fail("must be [min, max] with min <= max");
        return r;
    }
    // A name shown in files and messages: not empty, at most 200 bytes, no control characters.
    std::string name() const {
        const std::string s = string();
        checkName(*this, s);
        return s;
    }
    // The same rules for a name that is an object's key (`at` is the value it names).
    static void checkName(const Reader& at, const std::string& s) {
        if (s.empty()) at.fail("a name must not be empty");
        if (s.size() > 200) at.fail("a name must be at most 200 bytes, got " + std::to_string(s.size()));
        for (const char c : s)
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
                at.fail("a name must not hold control characters (found byte " + std::to_string(int(static_cast<unsigned char>(c))) + ")");
    }

private:
    static std::string unitOf(const SceneRange& r) { return *r.unit ? std::string(" ") + r.unit : std::string(); }
    std::string typeName() const { return v_.is_null() ? "null" : v_.type_name(); }
    // As people write numbers: 1000000 and 0.5, but 1e+300.
    static std::string fmt(double d) {
        char text[64];
        if (d == std::floor(d) && std::fabs(d) < 1e15) std::snprintf(text, sizeof text, "%.0f", d);
        else std::snprintf(text, sizeof text, "%.10g", d);
        return text;
    }
    const json& v_;
    std::string path_;
    const std::string& file_;
};

// Band ends, metres: at least one, each within `key`'s range, increasing.
std::vector<double> levelEnds(const Reader& r, const char* section, const char* key) {
    if (r.array() == 0) r.fail("must list at least one distance (leave it out for the defaults)");
    std::vector<double> out;
    for (std::size_t i = 0; i < r.array(); ++i) {
        out.push_back(r.at(i).within(section, key));
        if (i > 0 && out[i] <= out[i - 1]) r.at(i).fail("level ends must increase");
    }
    return out;
}

// A path in the file, relative to the scene's folder, naming what it should be and is not.
enum class PathKind { Folder, GltfFile };

std::string existingPath(const Reader& r, const std::string& base, PathKind kind) {
    const std::string p = r.string();
    if (p.empty()) r.fail("must not be empty");
    const fs::path full = (fs::path(base) / p).lexically_normal();
    const std::string shown = "'" + full.string() + "'";
    std::error_code ec;
    const fs::file_status status = fs::status(full, ec);
    if (!fs::exists(status)) r.fail(std::string(kind == PathKind::Folder ? "folder " : "file ") + shown + " does not exist");
    if (kind == PathKind::Folder) {
        if (!fs::is_directory(status)) r.fail(shown + " is a file, not a folder");
        return full.string();
    }
    if (fs::is_directory(status)) r.fail(shown + " is a folder, not a glTF file");
    if (!fs::is_regular_file(status)) r.fail(shown + " is not a regular file");
    // A glTF file is binary ("glTF" first) or JSON ('{' first, after spaces and a byte-order mark).
    std::ifstream in(full, std::ios::binary);
    char head[64] = {};
    in.read(head, sizeof head);
    const std::size_t n = static_cast<std::size_t>(in.gcount());
    if (n == 0) r.fail("file " + shown + " is empty");
    std::string_view start(head, n);
    if (start.rfind("glTF", 0) == 0) return full.string();
    if (start.rfind("\xEF\xBB\xBF", 0) == 0) start.remove_prefix(3);
    const std::size_t first = start.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos || start[first] != '{')
        r.fail(shown + " is not a glTF file (a .glb starts with 'glTF', a .gltf is a JSON object)");
    return full.string();
}

const char* kProcedural[] = {"seed-humanoid", "table3", "bird"};

// Geometric LOD levels {until, share of triangles}, nearest first (templates and the town).
std::vector<glm::dvec2> geometricLevels(const Reader& lod) {
    const std::size_t n = lod.array();
    if (n == 0) lod.fail("must hold at least one level");
    std::vector<glm::dvec2> out;
    double previous = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const Reader level = lod.at(i);
        level.object({"until", "triangles"});
        double until = std::numeric_limits<double>::infinity();
        if (level.has("until")) until = level.at("until").within("lod levels", "until");
        else if (i + 1 < n) level.fail("needs 'until': only the last level may reach to any distance");
        if (!(until > previous)) level.at("until").fail("must exceed the previous level's distance");
        const double share = level.has("triangles") ? level.at("triangles").within("lod levels", "triangles") : 1.0;
        out.push_back({until, share});
        previous = until;
    }
    return out;
}

// "walkways": walkable floor rectangles instead of a town, and the navigation mesh's voxel.
void readWalkways(const Reader& root, SceneDescription& s) {
    const Reader w = root.at("walkways");
    w.object({"floors", "cellSize", "bodyRadius"});
    WalkwaysDescription walkways;
    const Reader floors = w.at("floors");
    const std::size_t n = floors.array();
    if (n == 0) floors.fail("must list at least one floor rectangle");
    for (std::size_t i = 0; i < n; ++i) {
        const Reader f = floors.at(i);
        f.object({"center", "size"});
        walkways.floors.push_back({f.at("center").vecWithin<2>("walkways", "floors[].center"),
                                   f.at("size").vecWithin<2>("walkways", "floors[].size")});
    }
    if (w.has("cellSize")) walkways.cellSize = w.at("cellSize").within("walkways", "cellSize");
    if (w.has("bodyRadius")) walkways.bodyRadius = w.at("bodyRadius").within("walkways", "bodyRadius");
    s.walkways = walkways;
}

// "town": the grid of blocks, its tiles, occluders, LOD levels and regions.
void readTown(const Reader& root, SceneDescription& s, const std::string& baseDirectory, const std::string& file) {
    const Reader t = root.at("town");
    t.object({"blocksX", "blocksZ", "blockTiles", "tileSize", "seed", "tiles", "occluders", "lod", "lodScale", "regions"});
    TownDescription town;
    if (t.has("blocksX")) town.blocksX = int(t.at("blocksX").wholeWithin("town", "blocksX"));
    if (t.has("blocksZ")) town.blocksZ = int(t.at("blocksZ").wholeWithin("town", "blocksZ"));
    if (t.has("blockTiles")) town.blockTiles = int(t.at("blockTiles").wholeWithin("town", "blockTiles"));
    if (t.has("tileSize")) town.tileSize = t.at("tileSize").within("town", "tileSize");
    if (t.has("seed")) town.seed = static_cast<std::uint64_t>(t.at("seed").atLeast(0));
    if (t.has("occluders")) town.occluders = t.at("occluders").boolean();
    if (t.has("lod")) town.lod = geometricLevels(t.at("lod"));
    if (t.has("lodScale")) {
        if (!t.has("lod")) t.at("lodScale").fail("needs the town's 'lod' levels");
        town.lodScale = t.at("lodScale").within("town", "lodScale");
    }
    if (t.has("regions")) {
        // {"size": [bx, bz]}: rectangles of so many blocks; or a list of {"from": [x, z], "to": [x, z]} (blocks, 'to' excluded).
        const Reader r = t.at("regions");
        const auto blocks = [](const Reader& v) {
            const glm::dvec2 b = v.vec<2>();
            if (b.x != std::floor(b.x) || b.y != std::floor(b.y) || b.x < 0 || b.y < 0 || b.x > 1e6 || b.y > 1e6)
                v.fail("must be two whole numbers of blocks");
            return glm::ivec2(b);
        };
        if (r.value().is_object()) {
            r.object({"size"});
            town.regionBlocks = blocks(r.at("size"));
            if (town.regionBlocks.x < 1 || town.regionBlocks.y < 1) r.at("size").fail("must be at least one block each way");
        } else {
            if (r.array() == 0) r.fail("must list at least one region");
            for (std::size_t i = 0; i < r.array(); ++i) {
                const Reader one = r.at(i);
                one.object({"from", "to"});
                town.regions.push_back({blocks(one.at("from")), blocks(one.at("to"))});
            }
        }
    }
    town.tiles = existingPath(t.at("tiles"), baseDirectory, PathKind::Folder);
    for (const char* needed : {"road-straight.glb", "road-corner.glb", "road-split.glb", "road-intersection.glb", "pavement.glb"})
        if (!fs::is_regular_file(fs::path(town.tiles) / needed))
            t.at("tiles").fail("has no '" + std::string(needed) + "'");
    const std::int64_t tiles = (std::int64_t(town.blocksX) * (town.blockTiles + 1) + 1) * (std::int64_t(town.blocksZ) * (town.blockTiles + 1) + 1);
    if (tiles > kMaxTownTiles) t.fail("is too large (" + std::to_string(tiles) + " tiles, more than " + std::to_string(kMaxTownTiles) + ")");
    townRegions(town, file);  // every block in exactly one region
    s.town = town;
}

// "effects.face", "effects.blink", "effects.phrase": faces, each only where declared.
void readFaces(const Reader& e, SceneDescription& s) {
    FaceLayer::Settings& f = s.effects.faces;
    // `true` (the defaults) or an object of the given keys.
    const auto declared = [&](const char* key, std::initializer_list<const char*> keys) {
        if (!e.has(key)) return false;
        const Reader r = e.at(key);
        if (r.value().is_boolean()) return r.boolean();
        r.object(keys);
        return true;
    };
    f.face = declared("face", {"levels", "transition", "expressions"});
    if (f.face && e.at("face").value().is_object()) {
        const Reader r = e.at("face");
        if (r.has("levels")) f.faceLevels = levelEnds(r.at("levels"), "effects", "face.levels");
        if (r.has("transition")) f.transition = r.at("transition").within("effects", "face.transition");
        if (r.has("expressions")) {
            const Reader list = r.at("expressions");
            if (list.array() == 0) list.fail("must list at least one expression (leave it out for one per morph target)");
            std::set<std::string> names;
            for (std::size_t i = 0; i < list.array(); ++i) {
                const Reader x = list.at(i);
                x.object({"name", "duration", "weights"});
                FaceLayer::Expression ex;
                ex.name = x.at("name").name();
                if (!names.insert(ex.name).second) x.at("name").fail("'" + ex.name + "' is already an expression");
                if (x.has("duration")) ex.duration = x.at("duration").within("effects", "face.expressions.duration");
                if (x.has("weights")) {
                    const Reader w = x.at("weights");
                    w.anyObject();
                    for (auto it = w.value().begin(); it != w.value().end(); ++it) {
                        const Reader one = w.at(it.key().c_str());
                        Reader::checkName(one, it.key());
                        ex.weights[it.key()] = float(one.within("effects", "face.expressions.weights"));
                    }
                }
                f.expressions.push_back(std::move(ex));
            }
        }
    }
    f.blink = declared("blink", {"levels", "mean", "spread", "duration"});
    if (f.blink && e.at("blink").value().is_object()) {
        const Reader r = e.at("blink");
        if (r.has("levels")) f.blinkLevels = levelEnds(r.at("levels"), "effects", "blink.levels");
        if (r.has("mean")) f.blinkMean = r.at("mean").within("effects", "blink.mean");
        if (r.has("spread")) f.blinkSpread = r.at("spread").within("effects", "blink.spread");
        if (r.has("duration")) f.blinkDuration = r.at("duration").within("effects", "blink.duration");
        if (!(f.blinkSpread < f.blinkMean)) r.at(r.has("spread") ? "spread" : "mean").fail("the spread must be below the mean");
        if (!(f.blinkDuration < f.blinkMean - f.blinkSpread))
            r.at(r.has("duration") ? "duration" : "mean").fail("a blink must be shorter than the shortest interval (mean - spread)");
    }
    f.phrase = declared("phrase", {"levels", "phrases", "lettersPerSecond", "pause", "groupSize", "mouthTargets"});
    if (f.phrase) {
        f.phrases = {"Good morning!", "Lovely weather today.", "Have you seen the market?", "See you later!"};
        if (e.at("phrase").value().is_object()) {
            const Reader r = e.at("phrase");
            if (r.has("levels")) f.phraseLevels = levelEnds(r.at("levels"), "effects", "phrase.levels");
            if (r.has("phrases")) {
                const Reader list = r.at("phrases");
                if (list.array() == 0) list.fail("must list at least one phrase (leave it out for the defaults)");
                f.phrases.clear();
                for (std::size_t i = 0; i < list.array(); ++i) f.phrases.push_back(list.at(i).name());
            }
            if (r.has("lettersPerSecond")) f.lettersPerSecond = r.at("lettersPerSecond").within("effects", "phrase.lettersPerSecond");
            if (r.has("pause")) f.pause = r.at("pause").within("effects", "phrase.pause");
            if (r.has("groupSize")) s.effects.phraseGroupSize = int(r.at("groupSize").wholeWithin("effects", "phrase.groupSize"));
            if (r.has("mouthTargets")) {
                const Reader list = r.at("mouthTargets");
                for (std::size_t i = 0; i < list.array(); ++i) f.mouthTargets.push_back(list.at(i).name());
            }
        }
    }
}

// "effects": avoidance, gaze, far updates and faces, each only where declared.
void readEffects(const Reader& root, SceneDescription& s) {
    const Reader e = root.at("effects");
    e.object({"avoidance", "gaze", "farUpdate", "face", "blink", "phrase"});
    readFaces(e, s);
    if (e.has("avoidance")) {
        const Reader av = e.at("avoidance");
        if (av.value().is_boolean()) {
            s.effects.avoidance = av.boolean();
        } else {
            av.object({"model", "quality", "range"});
            s.effects.avoidance = true;
            if (av.has("model")) {
                const std::string model = av.at("model").string();
                if (model != "detour" && model != "orca") av.at("model").fail("must be \"detour\" or \"orca\", got \"" + model + "\"");
                s.effects.avoidanceModel = model;
                if (model == "orca" && av.has("quality")) av.at("quality").fail("is DetourCrowd's velocity sampling: ORCA has none");
            }
            if (av.has("quality")) s.effects.avoidanceQuality = int(av.at("quality").wholeWithin("effects", "avoidance.quality"));
            if (av.has("range")) s.effects.avoidanceRange = av.at("range").within("effects", "avoidance.range");
        }
    }
    if (e.has("farUpdate")) {  // an approximation: regions far from the camera step less often
        const Reader f = e.at("farUpdate");
        f.object({"distance", "every"});
        s.effects.farUpdateDistance = f.at("distance").within("effects", "farUpdate.distance");
        s.effects.farUpdateEvery = int(f.at("every").wholeWithin("effects", "farUpdate.every"));
    }
    if (e.has("gaze")) {
        const Reader g = e.at("gaze");
        if (g.value().is_boolean()) {
            s.effects.gaze = g.boolean();
        } else {
            g.object({"levels", "range"});
            s.effects.gaze = true;
            if (g.has("levels")) s.effects.gazeLevels = levelEnds(g.at("levels"), "effects", "gaze.levels");
            if (g.has("range")) s.effects.gazeRange = g.at("range").within("effects", "gaze.range");
        }
    }
}

// "representation": LOD scale, impostors, key-pose caches, occlusion.
void readRepresentation(const Reader& root, SceneDescription& s, const std::string& file) {
    const Reader r = root.at("representation");
    r.object({"impostorDistance", "impostorViews", "impostorSmoothstep", "impostorAtlas", "hysteresis", "lodScale", "occlusion", "keyPoseCache"});
    if (r.has("impostorDistance")) s.representation.impostorDistance = r.at("impostorDistance").within("representation", "impostorDistance");
    if (r.has("impostorViews")) {
        const std::string views = r.at("impostorViews").string();
        if (views == "blend") s.representation.impostorViews = ImpostorViews::Blend;
        else if (views == "nearest") s.representation.impostorViews = ImpostorViews::Nearest;
        else if (views == "warped") s.representation.impostorViews = ImpostorViews::Warped;
        else r.at("impostorViews").fail("must be \"blend\", \"nearest\" or \"warped\", got \"" + views + "\"");
    }
    if (r.has("impostorAtlas")) {
        const std::string atlas = r.at("impostorAtlas").string();
        if (atlas == "full") s.representation.impostorAtlas = ImpostorAtlasStorage::Full;
        else if (atlas == "half-keyframes") s.representation.impostorAtlas = ImpostorAtlasStorage::HalfKeyframes;
        else if (atlas == "half") s.representation.impostorAtlas = ImpostorAtlasStorage::Half;
        else r.at("impostorAtlas").fail("must be \"full\", \"half-keyframes\" or \"half\", got \"" + atlas + "\"");
    }
    if (r.has("impostorSmoothstep")) {
        s.representation.impostorSmoothstep = r.at("impostorSmoothstep").boolean();
        if (s.representation.impostorSmoothstep && s.representation.impostorViews == ImpostorViews::Nearest)
            r.at("impostorSmoothstep").fail("applies to \"blend\" and \"warped\" only: impostorViews is \"nearest\"");
    }
    if (r.has("hysteresis")) s.representation.hysteresis = r.at("hysteresis").within("representation", "hysteresis");
    if (r.has("lodScale")) s.representation.lodScale = r.at("lodScale").within("representation", "lodScale");
    if (r.has("occlusion")) {
        const char* section = "representation.occlusion";
        const Reader o = r.at("occlusion");
        o.object({"width", "height", "maxOccluders", "rest"});
        OcclusionSettings settings;
        if (o.has("width")) settings.width = int(o.at("width").wholeWithin(section, "width"));
        if (o.has("height")) settings.height = int(o.at("height").wholeWithin(section, "height"));
        if (o.has("maxOccluders")) settings.maxOccluders = int(o.at("maxOccluders").wholeWithin(section, "maxOccluders"));
        // "rest": {"frames": N, "below": share, "wakeDistance": m, "wakeAngle": degrees}
        if (o.has("rest")) {
            const Reader rest = o.at("rest");
            rest.object({"frames", "below", "wakeDistance", "wakeAngle"});
            settings.restFrames = int(rest.at("frames").wholeWithin(section, "rest.frames"));
            if (rest.has("below")) settings.restBelow = rest.at("below").within(section, "rest.below");
            if (rest.has("wakeDistance")) settings.wakeDistance = rest.at("wakeDistance").within(section, "rest.wakeDistance");
            if (rest.has("wakeAngle")) settings.wakeAngleDegrees = rest.at("wakeAngle").within(section, "rest.wakeAngle");
        }
        s.representation.occlusion = settings;
    }
    if (r.has("keyPoseCache")) {
        const char* section = "representation.keyPoseCache";
        const Reader k = r.at("keyPoseCache");
        k.object({"distance", "mode", "keyPosesPerSecond", "rows"});
        KeyPoseCacheDescription cache;
        if (k.has("distance")) cache.distance = k.at("distance").within(section, "distance");
        if (k.has("mode")) {
            const std::string mode = k.at("mode").string();
            if (mode == "intermittent") cache.mode = KeyPoseMode::Intermittent;
            else if (mode == "interpolative") cache.mode = KeyPoseMode::Interpolative;
            else k.at("mode").fail("must be \"intermittent\" or \"interpolative\", got \"" + mode + "\"");
        }
        if (k.has("keyPosesPerSecond")) cache.keyPosesPerSecond = k.at("keyPosesPerSecond").within(section, "keyPosesPerSecond");
        const Reader rows = k.at("rows");
        rows.anyObject();  // its keys are template names
        for (auto it = rows.value().begin(); it != rows.value().end(); ++it) {
            const Reader row(it.value(), rows.path() + "/" + it.key(), file);
            if (!s.templates.count(it.key())) row.fail("names no declared template");
            cache.rows[it.key()] = static_cast<std::uint32_t>(row.wholeWithin(section, "rows"));
        }
        if (cache.rows.empty()) rows.fail("must give rows for at least one template");
        if (s.representation.impostorDistance > 0 && cache.distance >= s.representation.impostorDistance)
            k.at("distance").fail("must be below impostorDistance (" + std::to_string(s.representation.impostorDistance) +
                                  "): the band lies between skinned actors and impostors");
        s.representation.keyPoseCache = cache;
    }
}

// "camera": the path and the lens.
void readCamera(const Reader& root, SceneDescription& s) {
    const Reader c = root.at("camera");
    c.object({"fov", "near", "far", "path"});
    if (c.has("fov")) s.camera.fovDegrees = c.at("fov").within("camera", "fov");
    if (c.has("near")) s.camera.nearDistance = c.at("near").within("camera", "near");
    if (c.has("far")) s.camera.farDistance = c.at("far").within("camera", "far");
    if (s.camera.farDistance <= s.camera.nearDistance) c.fail("far must exceed near");
    if (c.has("path")) {
        const Reader path = c.at("path");
        if (path.array() == 0) path.fail("must hold at least one key (leave it out for the circling camera)");
        for (std::size_t i = 0; i < path.array(); ++i) {
            const Reader k = path.at(i);
            k.object({"time", "eye", "target"});
            CameraKey key;
            key.time = k.at("time").within("camera", "path[].time");
            key.eye = k.at("eye").vecWithin<3>("camera", "path[].eye");
            key.target = k.at("target").vecWithin<3>("camera", "path[].target");
            if (glm::length(key.target - key.eye) < 1e-6) k.at("target").fail("must differ from eye");
            if (i > 0 && key.time <= s.camera.path.back().time) k.at("time").fail("times must increase");
            s.camera.path.push_back(key);
        }
    }
}

// "looks": a count of generated looks, or a list of looks, each {"skin", "hair", "top",
// "bottom"} colours "#rrggbb".
std::vector<BodyLook> readLooks(const Reader& r) {
    if (r.value().is_number()) return generatedLooks(static_cast<int>(r.wholeWithin("templates", "looks")));
    const std::size_t n = r.array();
    if (n == 0) r.fail("must list at least one look");
    std::vector<BodyLook> looks;
    for (std::size_t i = 0; i < n; ++i) {
        const Reader l = r.at(i);
        l.object({"skin", "hair", "top", "bottom"});
        BodyLook look;
        for (std::size_t k = 0; k < kBodyRegionCount; ++k) {
            const std::string name(bodyRegionName(static_cast<BodyRegion>(k + 1)));
            const Reader c = l.at(name.c_str());
            try {
                look.rgba[k] = parseBodyColour(c.string());
            } catch (const std::invalid_argument& e) {
                c.fail(e.what());
            }
        }
        looks.push_back(look);
    }
    return looks;
}

// "templates": each a glTF file or a procedural character, with its clips, scale and LOD.
void readTemplates(const Reader& root, SceneDescription& s, const std::string& baseDirectory, const std::string& file) {
    const Reader templates = root.at("templates");
    templates.anyObject();  // its keys are template names
    for (auto it = templates.value().begin(); it != templates.value().end(); ++it) {
        const Reader t(it.value(), "/templates/" + it.key(), file);
        Reader::checkName(t, it.key());
        t.object({"gltf", "procedural", "walkClip", "runClip", "idleClip", "walkClipSpeed", "runClipSpeed", "scale", "lod", "jointMinAngle", "looks"});
        TemplateDescription d;
        if (t.has("gltf") == t.has("procedural")) t.fail("must give exactly one of 'gltf' and 'procedural'");
        if (t.has("gltf")) d.gltf = existingPath(t.at("gltf"), baseDirectory, PathKind::GltfFile);
        if (t.has("procedural")) {
            d.procedural = t.at("procedural").string();
            if (std::find(std::begin(kProcedural), std::end(kProcedural), d.procedural) == std::end(kProcedural))
                t.at("procedural").fail("'" + d.procedural + "' is not a procedural template (seed-humanoid, table3, bird)");
        }
        if (t.has("walkClip")) d.walkClip = t.at("walkClip").string();
        if (t.has("runClip")) d.runClip = t.at("runClip").string();
        if (t.has("idleClip")) d.idleClip = t.at("idleClip").string();
        if (t.has("walkClipSpeed")) d.walkClipSpeed = t.at("walkClipSpeed").within("templates", "walkClipSpeed");
        if (t.has("runClipSpeed")) d.runClipSpeed = t.at("runClipSpeed").within("templates", "runClipSpeed");
        if (!d.runClip.empty() && d.runClipSpeed <= d.walkClipSpeed) t.at("runClipSpeed").fail("must exceed walkClipSpeed");
        if ((t.has("scale") || t.has("lod") || t.has("jointMinAngle") || t.has("looks")) && !t.has("gltf"))
            t.fail("'scale', 'lod', 'jointMinAngle' and 'looks' apply to glTF templates only");
        if (t.has("looks")) d.looks = readLooks(t.at("looks"));
        if (t.has("jointMinAngle")) d.jointMinAngle = t.at("jointMinAngle").within("templates", "jointMinAngle");
        if (t.has("scale")) d.scale = t.at("scale").within("templates", "scale");
        if (t.has("lod")) d.lod = geometricLevels(t.at("lod"));
        s.templates[it.key()] = d;
    }
    if (s.templates.empty()) templates.fail("must declare at least one template");
}

// "actors": the groups, each of a declared template with its behaviour, area and levels.
void readActors(const Reader& root, SceneDescription& s) {
    const Reader actors = root.at("actors");
    std::map<std::string, std::size_t> names;  // group name -> its index, to refuse a repeated one
    for (std::size_t i = 0; i < actors.array(); ++i) {
        const Reader a = actors.at(i);
        a.object({"name", "template", "count", "behaviour", "area", "speed", "speedProfile", "goal", "period", "altitude", "groupSize", "levels",
                  "priority"});
        ActorGroupDescription g;
        g.name = a.has("name") ? a.at("name").name() : "group " + std::to_string(i);
        if (const auto [at, added] = names.emplace(g.name, i); !added)
            (a.has("name") ? a.at("name") : a).fail("repeats the name of /actors/" + std::to_string(at->second) + " ('" + g.name + "')");
        g.templateName = a.at("template").string();
        if (!s.templates.count(g.templateName)) a.at("template").fail("names no declared template ('" + g.templateName + "')");
        g.count = a.at("count").wholeWithin("actors", "count");
        g.behaviour = a.at("behaviour").string();
        if (g.behaviour != "walk" && g.behaviour != "idle" && g.behaviour != "flight")
            a.at("behaviour").fail("'" + g.behaviour + "' is not a behaviour (walk, idle, flight)");
        if (a.has("area")) {
            const Reader area = a.at("area");
            area.object({"center", "size"});
            if (area.has("center")) g.area.center = area.at("center").vecWithin<2>("actors", "area.center");
            if (area.has("size")) g.area.size = area.at("size").vecWithin<2>("actors", "area.size");
        }
        // Each of these means something for one behaviour only: given for another, it is a mistake.
        const auto onlyFor = [&](const char* key, bool applies, const char* which) {
            if (a.has(key) && !applies) a.at(key).fail(std::string("applies to ") + which + " only, not to '" + g.behaviour + "'");
            return a.has(key);
        };
        if (onlyFor("speed", g.behaviour != "idle", "walk and flight"))
            g.speed = a.at("speed").rangeWithin("actors", g.behaviour == "walk" ? "speed (walk)" : "speed (flight)");
        if (onlyFor("speedProfile", g.behaviour == "walk", "walk")) {
            if (a.has("speed")) a.at("speedProfile").fail("give 'speed' or 'speedProfile', not both");
            g.speedProfile = a.at("speedProfile").string();
            if (!findSpeedProfile(g.speedProfile)) {
                std::string known;
                for (const SpeedProfile& p : speedProfiles()) known += (known.empty() ? "" : ", ") + std::string(p.name);
                a.at("speedProfile").fail("'" + g.speedProfile + "' is not a speed profile (" + known + ")");
            }
        }
        if (onlyFor("goal", g.behaviour == "walk", "walk")) g.goal = a.at("goal").vecWithin<2>("actors", "goal");
        if (onlyFor("period", g.behaviour == "walk", "walk")) {
            g.period = a.at("period").vecWithin<2>("actors", "period");
            if (!g.goal || !s.walkways) a.at("period").fail("needs a 'goal' and walkways (the walkers re-enter before the goal)");
            if (glm::length(*g.period) < 2.0) a.at("period").fail("must be at least 2 m long");
        }
        if (onlyFor("altitude", g.behaviour == "flight", "flight")) g.altitude = a.at("altitude").rangeWithin("actors", "altitude");
        if (onlyFor("groupSize", g.behaviour == "idle", "idle")) {
            g.groupSize = glm::ivec2(a.at("groupSize").rangeWithin("actors", "groupSize"));
            if (g.count > 0 && g.groupSize.y > g.count)
                a.at("groupSize").fail("the largest group (" + std::to_string(g.groupSize.y) + ") is larger than 'count' (" +
                                       std::to_string(g.count) + ")");
        }
        if (a.has("levels")) g.levels = levelEnds(a.at("levels"), "actors", "levels");
        if (a.has("priority")) g.priority = a.at("priority").within("actors", "priority");
        if (g.behaviour == "walk" && !s.town && !s.walkways) a.at("behaviour").fail("'walk' needs a town or walkways to walk in");
        s.actors.push_back(g);
    }
}

// Larger than any scene needs (a scene describes its crowd, it does not list it); parsing more
// would take its size several times over in memory.
constexpr std::uintmax_t kMaxSceneBytes = 16u << 20;

}  // namespace

SceneDescription parseScene(const std::string& text, const std::string& baseDirectory, const std::string& file) {
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw SceneError(file, "", "is empty");
    if (text.size() > kMaxSceneBytes) throw SceneError(file, "", "is larger than 16 MiB (" + std::to_string(text.size()) + " bytes)");
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        // Say where, as a line and column, not just a byte offset.
        std::size_t line = 1, column = 1;
        for (std::size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
            if (text[i] == '\n') ++line, column = 1;
            else ++column;
        }
        throw SceneError(file, "", "is not valid JSON (line " + std::to_string(line) + ", column " + std::to_string(column) + ")");
    } catch (const json::out_of_range& e) {
        // A number beyond a double's range ("number overflow parsing '1e400'"): valid JSON, no usable value.
        const std::string what = e.what();
        const auto at = what.find("parsing ");
        std::string number = at == std::string::npos ? std::string() : what.substr(at + 8);
        std::erase(number, '\'');
        throw SceneError(file, "", "holds a number beyond a double's range" + (number.empty() ? std::string() : ": " + number));
    }
    const Reader root(doc, "", file);
    root.object({"name", "seed", "step", "town", "walkways", "templates", "actors", "effects", "representation", "camera"});
    SceneDescription s;
    s.baseDirectory = baseDirectory;
    s.file = file;
    if (root.has("name")) s.name = root.at("name").name();
    if (root.has("seed")) s.seed = static_cast<std::uint64_t>(root.at("seed").atLeast(0));
    if (root.has("step")) s.step = root.at("step").within("document", "step");

    if (root.has("town")) readTown(root, s, baseDirectory, file);
    if (root.has("walkways")) {
        if (root.has("town")) root.at("walkways").fail("give 'town' or 'walkways', not both");
        readWalkways(root, s);
    }

    readTemplates(root, s, baseDirectory, file);

    readActors(root, s);

    if (root.has("effects")) readEffects(root, s);

    if (root.has("representation")) readRepresentation(root, s, file);

    if (root.has("camera")) readCamera(root, s);
    return s;
}

SceneDescription parseSceneFile(const std::string& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw SceneError(path, "", "is a folder, not a scene file");
    if (const std::uintmax_t bytes = fs::file_size(path, ec); !ec && bytes > kMaxSceneBytes)
        throw SceneError(path, "", "is larger than 16 MiB (" + std::to_string(bytes) + " bytes)");
    std::ifstream in(path);
    if (!in) throw SceneError(path, "", "cannot be read");
    std::stringstream text;
    text << in.rdbuf();
    return parseScene(text.str(), fs::path(path).parent_path().string(), path);
}

}  // namespace throng::sim
