#include "throng/sim/SceneParser.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include <glm/geometric.hpp>

#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneError.h"
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

private:
    std::string typeName() const { return v_.is_null() ? "null" : v_.type_name(); }
    static std::string fmt(double d) {
        std::ostringstream s;
        s << d;
        return s.str();
    }
    const json& v_;
    std::string path_;
    const std::string& file_;
};

std::vector<double> levelEnds(const Reader& r) {
    std::vector<double> out;
    for (std::size_t i = 0; i < r.array(); ++i) {
        out.push_back(r.at(i).positive());
        if (i > 0 && out[i] <= out[i - 1]) r.at(i).fail("level ends must increase");
    }
    return out;
}

std::string existingFile(const Reader& r, const std::string& base, bool directory) {
    const std::string p = r.string();
    if (p.empty()) r.fail("must not be empty");
    const fs::path full = fs::path(base) / p;
    std::error_code ec;
    if (directory ? !fs::is_directory(full, ec) : !fs::is_regular_file(full, ec))
        r.fail(std::string(directory ? "folder" : "file") + " '" + full.lexically_normal().string() + "' does not exist");
    return full.lexically_normal().string();
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
        if (level.has("until")) until = level.at("until").positive();
        else if (i + 1 < n) level.fail("needs 'until': only the last level may reach to any distance");
        if (!(until > previous)) level.at("until").fail("must exceed the previous level's distance");
        const double share = level.has("triangles") ? level.at("triangles").positive() : 1.0;
        if (share > 1.0) level.at("triangles").fail("is a share of the triangles: at most 1");
        out.push_back({until, share});
        previous = until;
    }
    return out;
}

// "town": the grid of blocks, its tiles, occluders, LOD levels and regions.
void readTown(const Reader& root, SceneDescription& s, const std::string& baseDirectory, const std::string& file) {
    const Reader t = root.at("town");
    t.object({"blocksX", "blocksZ", "blockTiles", "tileSize", "seed", "tiles", "occluders", "lod", "lodScale", "regions"});
    TownDescription town;
    if (t.has("blocksX")) town.blocksX = int(t.at("blocksX").atLeast(1));
    if (t.has("blocksZ")) town.blocksZ = int(t.at("blocksZ").atLeast(1));
    if (t.has("blockTiles")) town.blockTiles = int(t.at("blockTiles").atLeast(1));
    if (t.has("tileSize")) town.tileSize = t.at("tileSize").positive();
    if (t.has("seed")) town.seed = static_cast<std::uint64_t>(t.at("seed").atLeast(0));
    if (t.has("occluders")) town.occluders = t.at("occluders").boolean();
    if (t.has("lod")) town.lod = geometricLevels(t.at("lod"));
    if (t.has("lodScale")) {
        if (!t.has("lod")) t.at("lodScale").fail("needs the town's 'lod' levels");
        town.lodScale = t.at("lodScale").positive();
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
    town.tiles = existingFile(t.at("tiles"), baseDirectory, true);
    for (const char* needed : {"road-straight.glb", "road-corner.glb", "road-split.glb", "road-intersection.glb", "pavement.glb"})
        if (!fs::is_regular_file(fs::path(town.tiles) / needed))
            t.at("tiles").fail("has no '" + std::string(needed) + "'");
    const std::int64_t tiles = (std::int64_t(town.blocksX) * (town.blockTiles + 1) + 1) * (std::int64_t(town.blocksZ) * (town.blockTiles + 1) + 1);
    if (tiles > kMaxTownTiles) t.fail("is too large (" + std::to_string(tiles) + " tiles, more than " + std::to_string(kMaxTownTiles) + ")");
    townRegions(town, file);  // every block in exactly one region
    s.town = town;
}

// "effects": avoidance, gaze and far updates, each only where declared.
void readEffects(const Reader& root, SceneDescription& s) {
    const Reader e = root.at("effects");
    e.object({"avoidance", "gaze", "farUpdate"});
    if (e.has("avoidance")) {
        const Reader av = e.at("avoidance");
        if (av.value().is_boolean()) {
            s.effects.avoidance = av.boolean();
        } else {
            av.object({"quality", "range"});
            s.effects.avoidance = true;
            if (av.has("quality")) {
                const double q = av.at("quality").number();
                if (q != std::floor(q) || q < 0 || q > 3) av.at("quality").fail("must be 0, 1, 2 or 3");
                s.effects.avoidanceQuality = static_cast<int>(q);
            }
            if (av.has("range")) {
                s.effects.avoidanceRange = av.at("range").positive();
                if (s.effects.avoidanceRange < 1.0) av.at("range").fail("must be at least 1 (agent radii)");
            }
        }
    }
    if (e.has("farUpdate")) {  // an approximation: regions far from the camera step less often
        const Reader f = e.at("farUpdate");
        f.object({"distance", "every"});
        s.effects.farUpdateDistance = f.at("distance").positive();
        const double every = f.at("every").number();
        if (every != std::floor(every) || every < 2 || every > 1000) f.at("every").fail("must be a whole number of steps from 2 to 1000");
        s.effects.farUpdateEvery = static_cast<int>(every);
    }
    if (e.has("gaze")) {
        const Reader g = e.at("gaze");
        if (g.value().is_boolean()) {
            s.effects.gaze = g.boolean();
        } else {
            g.object({"levels", "range"});
            s.effects.gaze = true;
            if (g.has("levels")) s.effects.gazeLevels = levelEnds(g.at("levels"));
            if (g.has("range")) s.effects.gazeRange = g.at("range").positive();
        }
    }
}

// "representation": LOD scale, impostors, key-pose caches, occlusion.
void readRepresentation(const Reader& root, SceneDescription& s, const std::string& file) {
    const Reader r = root.at("representation");
    r.object({"impostorDistance", "hysteresis", "lodScale", "occlusion", "keyPoseCache"});
    if (r.has("impostorDistance")) {
        s.representation.impostorDistance = r.at("impostorDistance").number();
        if (s.representation.impostorDistance < 0) r.at("impostorDistance").fail("must not be negative");
    }
    if (r.has("hysteresis")) {
        s.representation.hysteresis = r.at("hysteresis").number();
        if (s.representation.hysteresis < 0 || s.representation.hysteresis > 0.5) r.at("hysteresis").fail("must be in [0, 0.5]");
    }
    if (r.has("lodScale")) s.representation.lodScale = r.at("lodScale").positive();
    if (r.has("occlusion")) {
        const Reader o = r.at("occlusion");
        o.object({"width", "height", "maxOccluders", "rest"});
        OcclusionSettings settings;
        const auto size = [&](const char* key, int& into) {
            if (!o.has(key)) return;
            const std::int64_t v = o.at(key).atLeast(8);
            if (v > 4096) o.at(key).fail("must be at most 4096, got " + std::to_string(v));
            into = static_cast<int>(v);
        };
        size("width", settings.width);
        size("height", settings.height);
        if (o.has("maxOccluders")) {
            const std::int64_t v = o.at("maxOccluders").atLeast(1);
            if (v > 1000000) o.at("maxOccluders").fail("must be at most 1000000, got " + std::to_string(v));
            settings.maxOccluders = static_cast<int>(v);
        }
        // "rest": {"frames": N, "below": share, "wakeDistance": m, "wakeAngle": degrees}
        if (o.has("rest")) {
            const Reader rest = o.at("rest");
            rest.object({"frames", "below", "wakeDistance", "wakeAngle"});
            const std::int64_t frames = rest.at("frames").atLeast(1);
            if (frames > 1000) rest.at("frames").fail("must be at most 1000, got " + std::to_string(frames));
            settings.restFrames = static_cast<int>(frames);
            const auto bounded = [&](const char* key, double hi, double& into) {
                if (!rest.has(key)) return;
                const double v = rest.at(key).number();
                if (v < 0.0 || v > hi) rest.at(key).fail("must be in [0, " + std::to_string(static_cast<int>(hi)) + "]");
                into = v;
            };
            bounded("below", 1.0, settings.restBelow);
            bounded("wakeDistance", 1000000.0, settings.wakeDistance);
            bounded("wakeAngle", 180.0, settings.wakeAngleDegrees);
        }
        s.representation.occlusion = settings;
    }
    if (r.has("keyPoseCache")) {
        const Reader k = r.at("keyPoseCache");
        k.object({"distance", "mode", "keyPosesPerSecond", "rows"});
        KeyPoseCacheDescription cache;
        if (k.has("distance")) cache.distance = k.at("distance").positive();
        if (k.has("mode")) {
            const std::string mode = k.at("mode").string();
            if (mode == "intermittent") cache.mode = KeyPoseMode::Intermittent;
            else if (mode == "interpolative") cache.mode = KeyPoseMode::Interpolative;
            else k.at("mode").fail("must be \"intermittent\" or \"interpolative\", got \"" + mode + "\"");
        }
        if (k.has("keyPosesPerSecond")) {
            cache.keyPosesPerSecond = k.at("keyPosesPerSecond").positive();
            if (cache.keyPosesPerSecond > 1000) k.at("keyPosesPerSecond").fail("must be at most 1000");
        }
        const Reader rows = k.at("rows");
        rows.anyObject();  // its keys are template names
        for (auto it = rows.value().begin(); it != rows.value().end(); ++it) {
            const Reader row(it.value(), rows.path() + "/" + it.key(), file);
            if (!s.templates.count(it.key())) row.fail("names no declared template");
            const std::int64_t n = row.atLeast(1);
            if (n > 65535) row.fail("must be at most 65535, got " + std::to_string(n));
            cache.rows[it.key()] = static_cast<std::uint32_t>(n);
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
    if (c.has("fov")) {
        s.camera.fovDegrees = c.at("fov").positive();
        if (s.camera.fovDegrees >= 180.0) c.at("fov").fail("must be below 180 degrees");
    }
    if (c.has("near")) s.camera.nearDistance = c.at("near").positive();
    if (c.has("far")) s.camera.farDistance = c.at("far").positive();
    if (s.camera.farDistance <= s.camera.nearDistance) c.fail("far must exceed near");
    if (c.has("path")) {
        const Reader path = c.at("path");
        for (std::size_t i = 0; i < path.array(); ++i) {
            const Reader k = path.at(i);
            k.object({"time", "eye", "target"});
            CameraKey key;
            key.time = k.at("time").number();
            key.eye = k.at("eye").vec<3>();
            key.target = k.at("target").vec<3>();
            if (glm::length(key.target - key.eye) < 1e-6) k.at("target").fail("must differ from eye");
            if (i > 0 && key.time <= s.camera.path.back().time) k.at("time").fail("times must increase");
            s.camera.path.push_back(key);
        }
    }
}

// "templates": each a glTF file or a procedural character, with its clips, scale and LOD.
void readTemplates(const Reader& root, SceneDescription& s, const std::string& baseDirectory, const std::string& file) {
const Reader templates = root.at("templates");
templates.anyObject();  // its keys are template names
for (auto it = templates.value().begin(); it != templates.value().end(); ++it) {
    const Reader t(it.value(), "/templates/" + it.key(), file);
    t.object({"gltf", "procedural", "walkClip", "runClip", "idleClip", "walkClipSpeed", "runClipSpeed", "scale", "lod", "jointMinAngle"});
    TemplateDescription d;
    if (t.has("gltf") == t.has("procedural")) t.fail("must give exactly one of 'gltf' and 'procedural'");
    if (t.has("gltf")) d.gltf = existingFile(t.at("gltf"), baseDirectory, false);
    if (t.has("procedural")) {
        d.procedural = t.at("procedural").string();
        if (std::find(std::begin(kProcedural), std::end(kProcedural), d.procedural) == std::end(kProcedural))
            t.at("procedural").fail("'" + d.procedural + "' is not a procedural template (seed-humanoid, table3, bird)");
    }
    if (t.has("walkClip")) d.walkClip = t.at("walkClip").string();
    if (t.has("runClip")) d.runClip = t.at("runClip").string();
    if (t.has("idleClip")) d.idleClip = t.at("idleClip").string();
    if (t.has("walkClipSpeed")) d.walkClipSpeed = t.at("walkClipSpeed").positive();
    if (t.has("runClipSpeed")) d.runClipSpeed = t.at("runClipSpeed").positive();
    if (!d.runClip.empty() && d.runClipSpeed <= d.walkClipSpeed) t.at("runClipSpeed").fail("must exceed walkClipSpeed");
    if ((t.has("scale") || t.has("lod") || t.has("jointMinAngle")) && !t.has("gltf"))
        t.fail("'scale', 'lod' and 'jointMinAngle' apply to glTF templates only");
    if (t.has("jointMinAngle")) {
        d.jointMinAngle = t.at("jointMinAngle").number();
        if (!(d.jointMinAngle >= 0.0 && d.jointMinAngle < 0.1)) t.at("jointMinAngle").fail("must be in [0, 0.1) radians");
    }
    if (t.has("scale")) d.scale = t.at("scale").positive();
    if (t.has("lod")) d.lod = geometricLevels(t.at("lod"));
    s.templates[it.key()] = d;
}
if (s.templates.empty()) templates.fail("must declare at least one template");
}

// "actors": the groups, each of a declared template with its behaviour, area and levels.
void readActors(const Reader& root, SceneDescription& s) {
const Reader actors = root.at("actors");
for (std::size_t i = 0; i < actors.array(); ++i) {
    const Reader a = actors.at(i);
    a.object({"name", "template", "count", "behaviour", "area", "speed", "altitude", "groupSize", "levels", "priority"});
    ActorGroupDescription g;
    g.name = a.has("name") ? a.at("name").string() : "group " + std::to_string(i);
    g.templateName = a.at("template").string();
    if (!s.templates.count(g.templateName)) a.at("template").fail("names no declared template ('" + g.templateName + "')");
    g.count = a.at("count").atLeast(0);
    if (g.count > 2'000'000) a.at("count").fail("is more than 2,000,000");
    g.behaviour = a.at("behaviour").string();
    if (g.behaviour != "walk" && g.behaviour != "idle" && g.behaviour != "flight")
        a.at("behaviour").fail("'" + g.behaviour + "' is not a behaviour (walk, idle, flight)");
    if (a.has("area")) {
        const Reader area = a.at("area");
        area.object({"center", "size"});
        if (area.has("center")) g.area.center = area.at("center").vec<2>();
        if (area.has("size")) {
            g.area.size = area.at("size").vec<2>();
            if (!(g.area.size.x > 0 && g.area.size.y > 0)) area.at("size").fail("must be positive");
        }
    }
    if (a.has("speed")) g.speed = a.at("speed").range();
    if (a.has("altitude")) g.altitude = a.at("altitude").range();
    if (a.has("groupSize")) {
        const glm::dvec2 gs = a.at("groupSize").range();
        if (gs.x != std::floor(gs.x) || gs.y != std::floor(gs.y)) a.at("groupSize").fail("must be whole numbers");
        g.groupSize = glm::ivec2(gs);
    }
    if (a.has("levels")) g.levels = levelEnds(a.at("levels"));
    if (a.has("priority")) g.priority = a.at("priority").positive();
    if (g.behaviour == "walk" && !s.town) a.at("behaviour").fail("'walk' needs a town to walk in");
    s.actors.push_back(g);
}
}

}  // namespace

SceneDescription parseScene(const std::string& text, const std::string& baseDirectory, const std::string& file) {
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
    }
    const Reader root(doc, "", file);
    root.object({"name", "seed", "step", "town", "templates", "actors", "effects", "representation", "camera"});
    SceneDescription s;
    s.baseDirectory = baseDirectory;
    s.file = file;
    if (root.has("name")) s.name = root.at("name").string();
    if (root.has("seed")) s.seed = static_cast<std::uint64_t>(root.at("seed").atLeast(0));
    if (root.has("step")) {
        s.step = root.at("step").positive();
        if (s.step > 0.5) root.at("step").fail("must be at most 0.5 s");
    }

    if (root.has("town")) readTown(root, s, baseDirectory, file);

    readTemplates(root, s, baseDirectory, file);

    readActors(root, s);

    if (root.has("effects")) readEffects(root, s);

    if (root.has("representation")) readRepresentation(root, s, file);

    if (root.has("camera")) readCamera(root, s);
    return s;
}

SceneDescription parseSceneFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw SceneError(path, "", "cannot be read");
    std::stringstream text;
    text << in.rdbuf();
    return parseScene(text.str(), fs::path(path).parent_path().string(), path);
}

}  // namespace throng::sim
