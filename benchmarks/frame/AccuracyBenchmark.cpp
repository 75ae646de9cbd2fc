// bench_accuracy: the error of the frame a user sees, for every approximation ("knob") of the
// frame, beside what the setting costs in APP+CULL and DRAW (issue 18).
//
// The town world of a scene, scaled to `--actors`, steps once per tick outside every processor.
// Each setting has its own ActorProcessor and CrowdRenderer on the identical simulation state (the
// state digest is checked after every processor of every tick), the settings take turns going
// first, the GL is finished after each pass. The reference renders each tick with every
// approximation off: skinned meshes everywhere (no impostors, no key-pose caches), all joints
// (skeletal LOD off), behaviours at level 0 (behavioural LOD off), geometric level 0 for every actor
// (LOD scale 1e-6, as throng-costmodel's full detail) and no occlusion culling.
//
// Convention: each setting turns on ONE knob over the reference, everything else off, so its error
// is that knob's alone. Every LOD decision compares a scaled eye distance (distance x LOD scale /
// priority), so at the reference's LOD scale the tier distances (impostors, key-pose band) and the
// behaviour bands are given scaled too (x 1e-6): the same actors change tier or level as at LOD
// scale 1, while every mesh stays at level 0. Some knobs need other worlds, built from the scene
// patched; each must step to the main world's digest, and its `off` setting must reproduce the
// reference image exactly (so the patch changed nothing else):
//   - skeletal LOD (a world per jointMinAngle, a template load option): LOD scale 1, with the glTF
//     templates' geometric levels removed (the full mesh at every distance) and the other
//     templates' actors (the procedural bird, whose own levels and joints stay as built) at detail
//     priority 1e6, so only the glTF joints switch off;
//   - behavioural LOD: a world with every behaviour's bands scaled, and one per behaviour (walk,
//     idle, flight, the gaze layer) with only its bands scaled, so only it lowers its level.
//
// Metrics per setting and camera ("street", "overview"), averaged over the measured ticks, against
// the reference of the same tick: PSNR (identical images capped at 99 dB), SSIM, share of pixels
// off by more than 8/255; where the knob changes poses, joint-position error (mean and max, mm,
// world space) of the actors posed in both, read from the draw lists (testkit::DrawnJoints: the joints
// where the palette, or the key-pose cache, puts them). A knob's `off` setting builds nothing for
// it (no impostor loaded, no cache made, no occlusion buffer), so it holds no memory; the `off` rows
// of the impostor knobs share one measurement, as do the key-pose cache's. Settings equal to
// another knob's (the scene's impostor distance, hysteresis, morph budget and bake; 32 rows,
// intermittent) are measured once and reported under each. Memory: impostor texture bytes, key-pose
// palettes and GPU rows, occlusion buffer and pyramid floats.
//
// usage: bench_accuracy --help

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "throng/bench/Experiment.h"
#include "throng/bench/FrameWorld.h"
#include "throng/bench/ResultTable.h"
#include "throng/bench/SameState.h"
#include "throng/testkit/Assets.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/testkit/DrawnJoints.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/testkit/ImageSimilarity.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/AccuracyCsv.h"

using namespace throng;

namespace {

constexpr const char* kProgram = "bench_accuracy";
constexpr double kFullDetail = 1e-6;  // LOD scale of the reference: every scaled distance ~0

[[noreturn]] void fail(const std::string& why) { bench::fail(kProgram, why); }

const std::vector<std::string> kKnobs{"lod-scale",         "skeletal-lod",        "behavioural-lod",  "impostor-distance",
                                      "impostor-hysteresis", "impostor-features", "impostor-morph-budget",
                                      "impostor-resolution", "impostor-views",    "impostor-keyframes", "key-pose-rows",
                                      "key-pose-mode",       "occlusion-resolution", "render-scale",     "town-lod"};

// The experiment's settings: the common ones (e) and its own.
struct Options {
    bench::ExperimentSpec e;  // scene, actors (one count), cameras, measured ticks per camera, warmup, size, outputs
    std::vector<std::string> knobs = kKnobs;
    std::vector<double> lodScales{0.5, 1.0, 2.0};
    std::vector<double> jointAngles{0.001, 0.004, 0.016};
    std::vector<double> impostorDistances{20, 40, 80};
    std::vector<double> hystereses{0.0, 0.1, 0.3};
    std::vector<std::int64_t> features{2, 8, 1000};
    std::vector<std::int64_t> budgets{0, 2, 16, -1};
    std::vector<std::int64_t> cellSizes{32, 64, 128};
    std::vector<std::int64_t> azimuths{8, 16};
    std::vector<std::int64_t> keyframes{8, 16};
    std::vector<std::int64_t> cacheRows{8, 32, 128};
    std::vector<std::string> occlusion{"64x36", "256x144", "1024x576"};
    std::vector<double> renderScales{0.75, 0.5, 0.35};
    std::vector<double> townLodScales{1.0, 3.0};
    bool has(const std::string& k) const { return std::find(knobs.begin(), knobs.end(), k) != knobs.end(); }
};

// A row of the report: the knob, its value, and whether it switches the knob off.
struct Label {
    std::string knob, value;
    bool off = false;
};

// The bake of an impostor set (throng-town's: 64 px cells, 16 x 4 views, 16 key-frames).
struct Bake {
    int cellSize = 64, azimuths = 16, elevations = 4, keyframes = 16;
    bool operator<(const Bake& b) const {
        return std::tie(cellSize, azimuths, elevations, keyframes) < std::tie(b.cellSize, b.azimuths, b.elevations, b.keyframes);
    }
};

// Means over the measured ticks of one setting on one camera.
struct Figures {
    double appCull = 0, draw = 0, psnr = 0, ssim = 0, off8 = 0, ticks = 0, memory = 0;
    JointError joints;
};

// One setting: the knobs of its processor and renderer, and the world it runs on.
struct Setting {
    std::vector<Label> labels;   // rows reporting it (none: the reference)
    std::size_t world = 0;
    double lodScale = kFullDetail;
    bool skeletalLod = false, behaviouralLod = false, poses = false;
    std::optional<Bake> impostors;    // attached impostors (distance 0: attached but off)
    double impostorDistance = 0, hysteresis = 0;  // metres at LOD scale 1
    std::optional<KeyPoseCacheSettings> cache;
    double cacheDistance = 0, cacheHysteresis = 0;
    std::optional<OcclusionSettings> occlusion;
    double townLodScale = 0;  // the town's levels at this LOD scale (0: the scene's, levels unused)
    CrowdRendererOptions renderer;
    std::unique_ptr<ActorProcessor> processor;
    std::unique_ptr<CrowdRenderer> draw;
    std::size_t cacheBytes = 0;
    std::map<std::string, Figures> figures;  // per camera
    Image frame;
    testkit::DrawnJoints joints;
};

struct World {
    std::string name;
    std::unique_ptr<sim::Simulation> sim;
};

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// "WxH" as a buffer resolution, sides in [8, 4096]; nullopt if it is not one.
std::optional<std::pair<int, int>> resolution(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    std::istringstream in(text);
    if (!(in >> w >> x >> h) || x != 'x' || in >> extra || w < 8 || h < 8 || w > 4096 || h > 4096) return std::nullopt;
    return std::make_pair(w, h);
}

sim::SceneDescription scaledScene(const Options& o) {
    sim::SceneDescription d = sim::parseSceneFile(o.e.scene);
    if (o.e.actors.front() > 0) sim::scaleActors(d, o.e.actors.front());
    return d;
}

// The scene for skeletal LOD at LOD scale 1 changing nothing else: every glTF template's joint
// angle `angle` and no geometric levels (its full mesh at every distance), no town levels, and the
// other templates' actors (the procedural bird, with geometric levels of its own) at detail
// priority 1e6, so that they stay at full detail.
sim::SceneDescription skeletalScene(const Options& o, double angle) {
    sim::SceneDescription d = scaledScene(o);
    std::set<std::string> gltf;
    for (auto& [name, t] : d.templates)
        if (!t.gltf.empty()) {
            t.lod.clear();
            t.jointMinAngle = angle;
            gltf.insert(name);
        }
    if (d.town) d.town->lod.clear();
    for (auto& g : d.actors)
        if (!gltf.count(g.templateName)) g.priority = 1e6;
    return d;
}

// The bands of a group as the simulation uses them (empty: its default).
std::vector<double> bandsOf(const sim::ActorGroupDescription& g) {
    return g.levels.empty() ? std::vector<double>{60.0, std::numeric_limits<double>::infinity()} : g.levels;
}

// The scene for behavioural LOD at the reference's LOD scale: the bands of `behaviour` ("gaze" for
// the gaze layer, "" for every one) scaled by it, so they fall where they do at LOD scale 1; the
// others' bands, compared with scaled distances near 0, keep level 0.
sim::SceneDescription behaviourScene(const Options& o, const std::string& behaviour) {
    sim::SceneDescription d = scaledScene(o);
    const auto scale = [](std::vector<double> bands) {
        for (double& b : bands) b *= kFullDetail;
        return bands;
    };
    for (auto& g : d.actors)
        if (behaviour.empty() || g.behaviour == behaviour) g.levels = scale(bandsOf(g));
    if (behaviour.empty() || behaviour == "gaze") d.effects.gazeLevels = scale(d.effects.gazeLevels);
    return d;
}

class AccuracyRun {
public:
    AccuracyRun(const Options& o, std::shared_ptr<GlContext> context) : o_(o), context_(std::move(context)) {}

    void run() {
        buildWorlds();
        defineSettings();
        buildSettings();
        measure();
    }
    const std::vector<Setting>& settings() const { return settings_; }
    std::size_t actors() const { return worlds_[0].sim->crowd().size(); }

private:
    const Options& o_;
    std::shared_ptr<GlContext> context_;
    std::vector<World> worlds_;
    std::map<Bake, std::unique_ptr<ImpostorSet>> bakes_;
    std::vector<Setting> settings_;
    std::size_t allBands_ = 0;                  // the world with every behaviour's bands live
    std::map<double, std::size_t> angleWorld_;  // joint angle -> world
    std::vector<std::pair<std::string, std::size_t>> behaviourWorlds_;
    double sceneTownLodScale_ = 1.0;  // the scene's town LOD scale (every world is built from it)

    std::size_t addWorld(std::string name, sim::SceneDescription d) {
        std::fprintf(stderr, "%s: building world '%s'\n", kProgram, name.c_str());
        worlds_.push_back({std::move(name), sim::Simulation::build(std::move(d))});
        return worlds_.size() - 1;
    }

    void buildWorlds() {
        addWorld("scene", scaledScene(o_));
        sceneTownLodScale_ = worlds_[0].sim->townLodScale();
        if (o_.has("skeletal-lod"))
            for (double angle : o_.jointAngles) angleWorld_[angle] = addWorld("joint angle " + number(angle), skeletalScene(o_, angle));
        if (!o_.has("behavioural-lod")) return;
        const sim::SceneDescription& scene = worlds_[0].sim->description();
        allBands_ = addWorld("every behaviour's bands", behaviourScene(o_, ""));
        std::vector<std::string> behaviours;
        for (const auto& g : scene.actors)
            if (std::find(behaviours.begin(), behaviours.end(), g.behaviour) == behaviours.end()) behaviours.push_back(g.behaviour);
        if (scene.effects.gaze) behaviours.push_back("gaze");
        if (behaviours.size() < 2) return;  // one behaviour: "every behaviour" is that one
        for (const std::string& b : behaviours) behaviourWorlds_.push_back({b, addWorld("bands of " + b + " alone", behaviourScene(o_, b))});
    }

    Setting& add(std::vector<Label> labels, std::size_t world = 0) {
        settings_.emplace_back();
        settings_.back().labels = std::move(labels);
        settings_.back().world = world;
        return settings_.back();
    }

    // The scene's renderer options with the GL finished after each pass.
    static CrowdRendererOptions finished() {
        CrowdRendererOptions r;
        r.finishPasses = true;
        return r;
    }

    void defineSettings() {
        const sim::Simulation& w = *worlds_[0].sim;
        const auto& declared = w.description().representation;
        const auto [distance, hysteresisM] = bench::impostorDistance(w);
        const double hysteresis = hysteresisM / distance;  // as a fraction
        add({}).renderer = finished();  // the reference
        if (o_.has("lod-scale")) {
            add({{"lod scale", "off (1e-6: level 0 everywhere)", true}}).renderer = finished();
            for (double s : o_.lodScales) {
                Setting& m = add({{"lod scale", number(s)}});
                m.lodScale = s;
                m.renderer = finished();
            }
        }
        if (!angleWorld_.empty()) {
            // Off: skeletal LOD switched off in a world where it would act (LOD scale 1).
            Setting& off = add({{"skeletal lod joint min angle", "off", true}}, angleWorld_.begin()->second);
            off.lodScale = 1.0;
            off.poses = true;
            off.renderer = finished();
        }
        for (const auto& [angle, world] : angleWorld_) {
            Setting& m = add({{"skeletal lod joint min angle", number(angle) + " rad"}}, world);
            m.lodScale = 1.0;
            m.skeletalLod = true;
            m.poses = true;
            m.renderer = finished();
        }
        if (o_.has("behavioural-lod")) {
            Setting& off = add({{"behavioural lod", "off", true}}, allBands_);
            off.poses = true;
            off.renderer = finished();
            Setting& all = add({{"behavioural lod", "every behaviour (scene bands)"}}, allBands_);
            all.behaviouralLod = true;
            all.poses = true;
            all.renderer = finished();
            for (const auto& [name, world] : behaviourWorlds_) {
                Setting& m = add({{"behavioural lod", name + " alone"}}, world);
                m.behaviouralLod = true;
                m.poses = true;
                m.renderer = finished();
            }
        }
        defineImpostors(distance, hysteresis);
        if ((o_.has("key-pose-rows") || o_.has("key-pose-mode")) && declared.keyPoseCache) {
            const auto& kp = *declared.keyPoseCache;
            std::vector<Label> off;
            if (o_.has("key-pose-rows")) off.push_back({"key-pose cache rows", "off", true});
            if (o_.has("key-pose-mode")) off.push_back({"key-pose cache mode", "off", true});
            const auto cacheSetting = [&](std::vector<Label> labels, std::uint32_t rows, KeyPoseMode mode, bool on) {
                Setting& m = add(std::move(labels));
                KeyPoseCacheSettings s;
                s.rows = rows;
                s.mode = mode;
                s.keyPosesPerSecond = kp.keyPosesPerSecond;
                if (on) m.cache = s;  // off: no cache built, as throng-town --key-pose-cache off
                m.cacheDistance = kp.distance;
                m.cacheHysteresis = declared.hysteresis * kp.distance;
                m.poses = true;
                m.renderer = finished();
            };
            cacheSetting(off, 32, kp.mode, false);
            for (std::int64_t rows : o_.cacheRows) {
                std::vector<Label> l{{"key-pose cache rows", std::to_string(rows)}};
                if (rows == 32 && o_.has("key-pose-mode")) l.push_back({"key-pose cache mode", "intermittent"});
                if (!o_.has("key-pose-rows")) l.erase(l.begin());
                if (!l.empty()) cacheSetting(l, std::uint32_t(rows), KeyPoseMode::Intermittent, true);
            }
            if (o_.has("key-pose-mode")) {
                if (!o_.has("key-pose-rows") || std::find(o_.cacheRows.begin(), o_.cacheRows.end(), 32) == o_.cacheRows.end())
                    cacheSetting({{"key-pose cache mode", "intermittent"}}, 32, KeyPoseMode::Intermittent, true);
                cacheSetting({{"key-pose cache mode", "interpolative"}}, 32, KeyPoseMode::Interpolative, true);
            }
        } else if (o_.has("key-pose-rows") || o_.has("key-pose-mode")) {
            std::fprintf(stderr, "%s: the scene declares no key-pose cache: its knobs are left out\n", kProgram);
        }
        if (o_.has("occlusion-resolution")) {
            const int occluders = declared.occlusion ? declared.occlusion->maxOccluders : 128;
            add({{"occlusion resolution", "off", true}}).renderer = finished();
            for (const std::string& r : o_.occlusion) {
                const auto [w2, h2] = *resolution(r);  // checked by the command line
                Setting& m = add({{"occlusion resolution", r}});
                m.occlusion = OcclusionSettings{w2, h2, occluders};
                m.renderer = finished();
            }
        }
        if (o_.has("render-scale")) {  // dynamic resolution: the frame drawn smaller and scaled up
            add({{"render scale", "off", true}}).renderer = finished();
            for (double r : o_.renderScales) {
                Setting& m = add({{"render scale", number(r)}});
                m.renderer = finished();
                m.renderer.renderScale = float(r);
            }
        }
        if (o_.has("town-lod")) {
            if (worlds_[0].sim->townHasLod()) {
                add({{"town lod scale", "off", true}}).renderer = finished();
                for (double t : o_.townLodScales) {
                    Setting& m = add({{"town lod scale", number(t)}});
                    m.townLodScale = t;
                    m.renderer = finished();
                }
            } else {
                std::fprintf(stderr, "%s: the scene builds no town LOD levels: its knob is left out\n", kProgram);
            }
        }
    }

    void defineImpostors(double distance, double hysteresis) {
        const std::vector<std::string> impostorKnobs{"impostor-distance",   "impostor-hysteresis", "impostor-features",
                                                     "impostor-morph-budget", "impostor-resolution", "impostor-views",
                                                     "impostor-keyframes"};
        std::vector<Label> off;
        const std::map<std::string, std::string> names{{"impostor-distance", "impostor distance"},
                                                       {"impostor-hysteresis", "impostor hysteresis"},
                                                       {"impostor-features", "impostor features"},
                                                       {"impostor-morph-budget", "impostor morph budget"},
                                                       {"impostor-resolution", "impostor resolution"},
                                                       {"impostor-views", "impostor views"},
                                                       {"impostor-keyframes", "impostor key-frames"}};
        for (const std::string& k : impostorKnobs)
            if (o_.has(k)) off.push_back({names.at(k), "off", true});
        if (off.empty()) return;
        const Bake scene;
        auto impostorSetting = [&](std::vector<Label> labels, Bake bake, double d, double h, CrowdRendererOptions r) {
            Setting& m = add(std::move(labels));
            m.impostors = bake;
            m.impostorDistance = d;
            m.hysteresis = h * d;
            m.renderer = r;
        };
        add(off).renderer = finished();  // off: no impostor attached or loaded
        // The scene's own setting (distance, hysteresis, default morphing, throng-town's bake).
        std::vector<Label> own;
        const auto has = [](const auto& v, auto x) { return std::find(v.begin(), v.end(), x) != v.end(); };
        if (o_.has("impostor-distance") && has(o_.impostorDistances, distance)) own.push_back({"impostor distance", number(distance) + " m"});
        if (o_.has("impostor-hysteresis") && has(o_.hystereses, hysteresis)) own.push_back({"impostor hysteresis", number(hysteresis)});
        const int defaultBudget = ImpostorRendererOptions{}.morphBudget;
        if (o_.has("impostor-morph-budget") && has(o_.budgets, std::int64_t(defaultBudget)))
            own.push_back({"impostor morph budget", std::to_string(defaultBudget)});
        if (o_.has("impostor-resolution") && has(o_.cellSizes, std::int64_t(scene.cellSize)))
            own.push_back({"impostor resolution", std::to_string(scene.cellSize) + " px"});
        if (o_.has("impostor-views") && has(o_.azimuths, std::int64_t(scene.azimuths)))
            own.push_back({"impostor views", std::to_string(scene.azimuths) + "x" + std::to_string(scene.elevations)});
        if (o_.has("impostor-keyframes") && has(o_.keyframes, std::int64_t(scene.keyframes)))
            own.push_back({"impostor key-frames", std::to_string(scene.keyframes)});
        if (!own.empty()) impostorSetting(own, scene, distance, hysteresis, finished());
        if (o_.has("impostor-distance"))
            for (double d : o_.impostorDistances)
                if (d != distance) impostorSetting({{"impostor distance", number(d) + " m"}}, scene, d, hysteresis, finished());
        if (o_.has("impostor-hysteresis"))
            for (double h : o_.hystereses)
                if (h != hysteresis) impostorSetting({{"impostor hysteresis", number(h)}}, scene, distance, h, finished());
        if (o_.has("impostor-morph-budget"))
            for (std::int64_t b : o_.budgets)
                if (b != defaultBudget) {
                    CrowdRendererOptions r = finished();
                    r.impostors.morphBudget = int(b);
                    impostorSetting({{"impostor morph budget", b < 0 ? std::string("unlimited") : std::to_string(b)}}, scene, distance,
                                    hysteresis, r);
                }
        if (o_.has("impostor-features"))
            for (std::int64_t f : o_.features) {
                // Every cell morphed along f feature lines by the GL (no budget), so the lines are the knob.
                CrowdRendererOptions r = finished();
                r.impostors.source = MorphSource::Gpu;
                r.impostors.warp = CellWarp::FeatureLines;
                r.impostors.morphBudget = -1;
                r.impostors.morph.features = std::size_t(f);
                impostorSetting({{"impostor features", f >= 1000 ? std::string("every bone") : std::to_string(f)}}, scene, distance,
                                hysteresis, r);
            }
        const auto rebake = [&](const std::string& knob, const std::string& value, Bake b) {
            impostorSetting({{knob, value}}, b, distance, hysteresis, finished());
        };
        if (o_.has("impostor-resolution"))
            for (std::int64_t c : o_.cellSizes)
                if (c != scene.cellSize) {
                    Bake b = scene;
                    b.cellSize = int(c);
                    rebake("impostor resolution", std::to_string(c) + " px", b);
                }
        if (o_.has("impostor-views"))
            for (std::int64_t a : o_.azimuths)
                if (a != scene.azimuths) {
                    Bake b = scene;
                    b.azimuths = int(a);
                    rebake("impostor views", std::to_string(a) + "x" + std::to_string(b.elevations), b);
                }
        if (o_.has("impostor-keyframes"))
            for (std::int64_t k : o_.keyframes)
                if (k != scene.keyframes) {
                    Bake b = scene;
                    b.keyframes = int(k);
                    rebake("impostor key-frames", std::to_string(k), b);
                }
    }

    ImpostorSet& bake(const Bake& b) {
        auto& set = bakes_[b];
        if (!set) {
            std::fprintf(stderr, "%s: baking impostors, %d px cells, %dx%d views, %d key-frames\n", kProgram, b.cellSize, b.azimuths,
                         b.elevations, b.keyframes);
            std::vector<ImpostorSet::Source> sources;
            for (const auto& t : worlds_[0].sim->templates()) sources.push_back({t.tmpl, t.clip});
            ImpostorBakeOptions options;
            options.cellSize = b.cellSize;
            options.azimuths = b.azimuths;
            options.elevations = b.elevations;
            options.keyframes = b.keyframes;
            set = std::make_unique<ImpostorSet>(context_, sources, options);
        }
        return *set;
    }

    void buildSettings() {
        for (Setting& m : settings_) {
            sim::Simulation& w = *worlds_[m.world].sim;
            m.processor = std::make_unique<ActorProcessor>(w.crowd());
            m.processor->setLodScale(m.lodScale);
            m.processor->setSkeletalLod(m.skeletalLod);
            m.processor->setBehaviouralLod(m.behaviouralLod);
            m.processor->setOcclusion(m.occlusion);
            // Tier distances at the processor's LOD scale: the same actors change tier as at scale 1.
            const double scale = m.lodScale;
            if (m.cache) {
                const auto& rows = w.description().representation.keyPoseCache->rows;
                for (const auto& t : w.templates()) {
                    if (!rows.count(t.name.substr(0, t.name.find('#')))) continue;
                    auto cache = std::make_shared<KeyPoseCache>(t.tmpl, *m.cache);
                    m.cacheBytes += cache->paletteBytes();
                    m.processor->setKeyPoseCache(std::move(cache));
                }
                m.processor->setKeyPoseDistance(m.cacheDistance * scale, m.cacheHysteresis * scale);
            }
            std::vector<std::shared_ptr<const ImpostorDrawable>> drawables;
            if (m.impostors) {
                ImpostorSet& set = bake(*m.impostors);
                set.attach(*m.processor, m.impostorDistance * scale, m.hysteresis * scale);
                for (std::size_t i = 0; i < set.size(); ++i) drawables.push_back(set.drawable(i));
            }
            context_->resize(o_.e.width, o_.e.height);
            m.draw = std::make_unique<CrowdRenderer>(context_, m.renderer);
            if (!drawables.empty()) m.draw->preloadImpostors(drawables);
        }
        std::fprintf(stderr, "%s: %zu settings on %zu worlds of %zu actors\n", kProgram, settings_.size(), worlds_.size(), actors());
    }

    // Steps every world once; all must reach the main world's state.
    std::uint64_t step(const std::string& camera) {
        for (World& w : worlds_) w.sim->step();
        const std::uint64_t digest = bench::stateDigest(worlds_[0].sim->crowd());
        for (const World& w : worlds_)
            if (bench::stateDigest(w.sim->crowd()) != digest)
                fail("world '" + w.name + "' stepped to another state than the scene's (" + camera + " camera, tick " +
                     std::to_string(worlds_[0].sim->now().frame) + ")");
        return digest;
    }

    void measure() {
        for (int f = 0; f < o_.e.warmup; ++f) step("warm-up");
        const double aspect = double(o_.e.width) / double(o_.e.height);
        for (const std::string& name : o_.e.cameras) {
            const Camera camera = worlds_[0].sim->camera().at(bench::cameraTime(name), aspect);
            for (int f = -1; f < o_.e.frames; ++f) {  // one unmeasured tick warms the GL, pools and caches
                step(name);
                bench::runOnSameStates(settings_.size(), f + 1, [&](std::size_t v) {
                    Setting& m = settings_[v];
                    sim::Simulation& w = *worlds_[m.world].sim;
                    // The town's levels at the setting's own scale (on top of its LOD scale), else the scene's.
                    w.setTownLodScale(m.townLodScale > 0 ? m.townLodScale / m.lodScale : sceneTownLodScale_);
                    const ActorFrameStatistics s = m.processor->processFrame(w.root(), camera, w.now().time);
                    Stopwatch watch;
                    m.draw->drawFrame(camera, m.processor->drawList());
                    const double drawMs = watch.elapsedMs();
                    if (f < 0) return;
                    Figures& fig = m.figures[name];
                    fig.appCull += s.appCullMs();
                    fig.draw += drawMs;
                    fig.ticks += 1;
                    m.frame = m.draw->readFrame();
                    if (m.poses || m.labels.empty()) m.joints.collect(m.processor->drawList(), w.crowd());
                }, [&](std::size_t v) { return bench::stateDigest(worlds_[settings_[v].world].sim->crowd()); },
                   [&](std::size_t v) { return label(settings_[v]); });
                if (f < 0) continue;
                const Setting& ref = settings_[0];
                for (std::size_t i = 1; i < settings_.size(); ++i) {
                    Setting& m = settings_[i];
                    Figures& fig = m.figures[name];
                    bench::addFrameError(m.frame, ref.frame, fig.psnr, fig.ssim, fig.off8);
                    if (m.poses) m.joints.compare(ref.joints, fig.joints);
                }
                std::fprintf(stderr, "%s: %s camera, tick %d of %d done\n", kProgram, name.c_str(), f + 1, o_.e.frames);
            }
            for (Setting& m : settings_) {
                Figures& fig = m.figures[name];
                const double n = std::max(fig.ticks, 1.0);
                fig.appCull /= n, fig.draw /= n, fig.psnr /= n, fig.ssim /= n, fig.off8 /= n;
                fig.memory = double(m.draw->impostorTextureBytes()) + double(m.cacheBytes) +
                             (m.cache ? double(m.draw->statistics().meshes.keyPoseCacheBytes) : 0.0) + occlusionBytes(m);
            }
        }
    }

    static double occlusionBytes(const Setting& m) {
        if (!m.occlusion) return 0;
        // The buffer of reciprocal depths and its pyramid of 2 x 2 maxima, floats.
        double bytes = 0;
        for (int w = m.occlusion->width, h = m.occlusion->height;; w = (w + 1) / 2, h = (h + 1) / 2) {
            bytes += double(w) * double(h) * sizeof(float);
            if (w <= 1 && h <= 1) break;
        }
        return bytes;
    }

    static std::string label(const Setting& m) {
        return m.labels.empty() ? std::string("the reference") : m.labels[0].knob + " " + m.labels[0].value;
    }
};

std::string table(const std::vector<Setting>& settings, const Options& o, std::size_t actors) {
    std::ostringstream out;
    out << "### " << actors << " actors, " << o.e.frames << " ticks per camera, " << o.e.width << "x" << o.e.height
        << ", each knob alone against every approximation off (ms per frame)\n\n";
    bench::ResultTable t({{"", "knob", "%s", true}, {"", "value", "%s", true}, {"", "camera", "%s", true}, {"", "PSNR dB", "%s"},
                          {"", "SSIM", "%s"}, {"", "pixels off > 8", "%s"}, {"", "joint error mean / max mm", "%s"}, {"", "APP+CULL", "%.2f"},
                          {"", "DRAW", "%.1f"}, {"", "memory MiB", "%s"}});
    char cell[64];
    const auto fixed = [&](const char* format, double v) {
        std::snprintf(cell, sizeof cell, format, v);
        return std::string(cell);
    };
    for (const std::string& camera : o.e.cameras) {
        const Figures& ref = settings[0].figures.at(camera);
        t.add({"reference (every approximation off)", "-", camera, "-", "-", "-", "-", ref.appCull, ref.draw, "0"});
    }
    for (const std::string& knob : [&] {
             std::vector<std::string> order;
             for (const Setting& m : settings)
                 for (const Label& l : m.labels)
                     if (std::find(order.begin(), order.end(), l.knob) == order.end()) order.push_back(l.knob);
             return order;
         }())
        for (const std::string& camera : o.e.cameras)
            for (bool off : {true, false})
                for (const Setting& m : settings)
                    for (const Label& l : m.labels) {
                        if (l.knob != knob || l.off != off) continue;
                        const Figures& f = m.figures.at(camera);
                        const std::string joints =
                            m.poses && f.joints.count() > 0 ? number(std::round(f.joints.meanMm() * 10) / 10) + " / " + number(std::round(f.joints.maxMm() * 10) / 10) : "-";
                        t.add({l.knob, l.value, camera, fixed("%.2f", f.psnr), fixed("%.4f", f.ssim), fixed("%.3f %%", 100.0 * f.off8), joints,
                               f.appCull, f.draw, fixed("%.2f", f.memory / 1048576.0)});
                    }
    return out.str() + t.markdown();
}

void writeCsv(const std::vector<Setting>& settings, const Options& o, std::size_t actors) {
    sim::AccuracyCsv csv(o.e.accuracyCsv);
    for (const Setting& m : settings)
        for (const Label& l : m.labels)
            for (const std::string& camera : o.e.cameras) {
                const Figures& f = m.figures.at(camera);
                sim::AccuracyRecord r;
                r.knob = l.knob;
                r.value = l.value;
                r.off = l.off;
                r.metrics = {{"psnr", f.psnr, "dB", false}, {"ssim", f.ssim, "1", false}, {"pixels_off_8", f.off8, "share", true}};
                if (m.poses && f.joints.count() > 0) {  // none when no actor was posed in both (rigid birds, impostors)
                    r.metrics.push_back({"joint_error_mean", f.joints.meanMm(), "mm", true});
                    r.metrics.push_back({"joint_error_max", f.joints.maxMm(), "mm", true});
                }
                r.ms = f.appCull + f.draw;
                r.msPhase = "app_cull+draw";
                r.memoryBytes = f.memory;
                r.scene = sim::sceneName(o.e.scene);
                r.camera = camera;
                r.actors = std::int64_t(actors);
                csv.add(r);
            }
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    bench::Experiment experiment(kProgram,
                                 "The error of the frame a user sees for each approximation alone (PSNR, SSIM, pixels off, joint "
                                 "error) against every approximation off, with its APP+CULL and DRAW time, on the identical state.",
                                 bench::kScene | bench::kActorCount | bench::kCameras | bench::kFrames | bench::kWarmup | bench::kImageSize |
                                     bench::kMarkdown | bench::kAccuracyCsv,
                                 {.scene = testkit::townDefaultScene(), .actors = {2000}, .cameras = {"street", "overview"}, .frames = 2, .warmup = 30},
                                 {.accuracyCsvHelp = "write every row in the common accuracy CSV"});
    CLI::App& app = experiment.app();
    app.add_option("--knobs", o.knobs, "knobs measured")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("NAME,...")->check(CLI::IsMember(kKnobs))
        ;
    app.add_option("--lod-scales", o.lodScales, "LOD scales (off: 1e-6)")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("S,...")->check(bench::finiteNumber(1e-6, 1e6))
        ;
    app.add_option("--joint-angles", o.jointAngles, "skeletal LOD jointMinAngle values, radians")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("A,...")
        ->check(bench::finiteNumber(1e-6, 0.099));
    app.add_option("--impostor-distances", o.impostorDistances, "impostor distances, m")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("M,...")
        ->check(bench::finiteNumber(1e-6, 1e6));
    app.add_option("--hystereses", o.hystereses, "impostor hystereses, fractions of the distance")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("F,...")
        ->check(bench::finiteNumber(0.0, 0.9));
    app.add_option("--features", o.features, "impostor feature lines (1000: every bone)")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("N,...")
        ->check(CLI::Range(0, 1000));
    app.add_option("--budgets", o.budgets, "impostor morph budgets, cells per atlas and frame (-1: unlimited)")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->type_name("N,...")->check(CLI::Range(-1, 100000));
    app.add_option("--cell-sizes", o.cellSizes, "impostor cell sizes, px (each another bake)")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("PX,...")
        ->check(CLI::Range(8, 512));
    app.add_option("--azimuths", o.azimuths, "impostor views around (each another bake)")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("N,...")
        ->check(CLI::Range(2, 64));
    app.add_option("--keyframes", o.keyframes, "impostor key-frames (each another bake)")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("N,...")
        ->check(CLI::Range(2, 128));
    app.add_option("--cache-rows", o.cacheRows, "key-pose cache rows per template")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("N,...")
        ->check(CLI::Range(1, 100000));
    app.add_option("--occlusion", o.occlusion, "occlusion buffer resolutions")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("WxH,...")
        ->check(CLI::Validator([](std::string& v) { return resolution(v) ? std::string() : "'" + v + "' is not WxH with sides in [8, 4096]"; },
                               ""))
        ;
    app.add_option("--render-scales", o.renderScales, "render scales (dynamic resolution; off: 1)")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("S,...")
        ->check(bench::finiteNumber(0.05, 0.99));
    app.add_option("--town-lod-scales", o.townLodScales, "LOD scales of the town's levels (off: the scene's)")->delimiter(',')->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->type_name("S,...")->check(bench::finiteNumber(1e-6, 1e6));
    if (const auto code = experiment.parse(argc, argv)) return *code;
    o.e = experiment.spec();
    std::string report;
    try {
        auto context = bench::experimentContext(o.e);
        AccuracyRun run(o, context);
        run.run();
        report = table(run.settings(), o, run.actors());
        if (!o.e.accuracyCsv.empty()) writeCsv(run.settings(), o, run.actors());
        std::fputs(report.c_str(), stdout);
        if (!o.e.markdown.empty()) bench::writeWhole(o.e.markdown, report);
    } catch (const std::exception& e) {
        fail(e.what());
    }
    return 0;
}
