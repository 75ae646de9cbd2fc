#include "throng/sim/Simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "throng/actors/ActorGroup.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/ElsewhereBehaviour.h"
#include "throng/actors/ProceduralBird.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/actors/Table3Template.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/gltf/MeshSimplifier.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"
#include "throng/scenegraph/Occluder.h"
#include "throng/scenegraph/OccluderFitting.h"
#include "throng/scenegraph/Transform.h"
#include "throng/scenegraph/ZOrder.h"
#include "throng/sim/CounterRng.h"
#include "throng/sim/Flock.h"
#include "throng/sim/GazeLayer.h"
#include "throng/sim/IdleGroups.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/Ranks.h"
#include "throng/sim/SceneError.h"
#include "throng/sim/SpeedProfile.h"
#include "throng/sim/CrowdLooks.h"
#include "throng/sim/TownRegions.h"

namespace throng::sim {
namespace {

// A template and its clips, resolved from a TemplateDescription.
struct ResolvedTemplate {
    std::shared_ptr<const ActorTemplate> tmpl;
    int walkClip = -1, runClip = -1, idleClip = -1;
    double walkClipSpeed = 1.4, runClipSpeed = 3.5;
    std::vector<BodyLook> looks;  // worn in turn by its actors (empty: as modelled)

    // `base` with the body look of the actor drawn from `stream`.
    ActorLook lookFor(const ActorLook& base, std::uint64_t stream) const {
        ActorLook look = base;
        if (!looks.empty()) look.body = lookForActor(looks, 0, stream);
        return look;
    }
};

int clipIndex(const ActorTemplate& t, const std::string& name, const std::string& file, const std::string& path) {
    if (name.empty()) return -1;
    const int i = t.findClip(name);
    if (i < 0) {
        std::string known;
        for (const auto& c : t.clips()) known += (known.empty() ? "" : ", ") + c->name();
        throw SceneError(file, path, "template '" + t.name() + "' has no clip named '" + name + "' (its clips: " +
                                         (known.empty() ? "none" : known) + ")");
    }
    return i;
}

ResolvedTemplate resolve(const std::string& key, const TemplateDescription& d, const std::string& file) {
    const std::string path = "/templates/" + key;
    ResolvedTemplate r;
    if (!d.gltf.empty()) {
        try {
            GltfLoadOptions options;
            options.scale = d.scale;
            options.jointMinAngle = d.jointMinAngle;
            options.bodyRegions = !d.looks.empty();
            for (const glm::dvec2& level : d.lod) options.lodLevels.push_back({level.x, level.y});
            r.tmpl = loadCharacter(d.gltf, options).primaryTemplate();
        } catch (const std::exception& e) {
            throw SceneError(file, path + "/gltf", e.what());
        }
        if (!r.tmpl) throw SceneError(file, path + "/gltf", "'" + d.gltf + "' holds no character");
    } else if (d.procedural == "seed-humanoid") {
        r.tmpl = makeSeedHumanoid();
    } else if (d.procedural == "table3") {
        r.tmpl = makeTable3Template();
    } else {
        r.tmpl = makeProceduralBird();
    }
    if (r.tmpl->clips().empty()) throw SceneError(file, path, "template '" + r.tmpl->name() + "' has no clip to play");
    r.walkClip = d.walkClip.empty() ? 0 : clipIndex(*r.tmpl, d.walkClip, file, path + "/walkClip");
    r.runClip = clipIndex(*r.tmpl, d.runClip, file, path + "/runClip");
    r.idleClip = clipIndex(*r.tmpl, d.idleClip, file, path + "/idleClip");
    r.walkClipSpeed = d.walkClipSpeed;
    r.runClipSpeed = d.runClipSpeed;
    r.looks = d.looks;
    return r;
}

// Turns about +Y by `quarterTurns` quarters: +Z goes to +X.
Mat4 tileTransform(const TownLayout& t, const TilePlacement& p) {
    const double a = p.quarterTurns * 0.5 * std::numbers::pi;
    Mat4 m(1.0);
    const double s = t.tileSize;
    m[0] = Vec4(std::cos(a) * s, 0.0, -std::sin(a) * s, 0.0);
    m[1] = Vec4(0.0, s, 0.0, 0.0);
    m[2] = Vec4(std::sin(a) * s, 0.0, std::cos(a) * s, 0.0);
    m[3] = Vec4(t.centre(p.x, p.z), 1.0);
    return m;
}

// Each tile model at every town LOD level, simplified once with meshoptimizer (share 1: the model).
using TownLevels = std::map<const MeshDrawable*, std::vector<std::shared_ptr<const MeshDrawable>>>;

// A tile model as the town shows it: its Geometry, or with town LOD (`lod` not empty) an LOD node
// choosing a level by the distance to the model's centre; beyond a last level's 'until', nothing.
std::shared_ptr<Node> tileModelNode(const std::shared_ptr<const MeshDrawable>& model, const std::vector<glm::dvec2>& lod,
                                    TownLevels& levels) {
    if (lod.empty()) return std::make_shared<Geometry>(model);
    auto& meshes = levels[model.get()];
    if (meshes.empty())
        for (const glm::dvec2& level : lod)
            meshes.push_back(level.y >= 1.0 ? model : std::make_shared<MeshDrawable>(simplifyMesh(model->mesh(), level.y).mesh));
    auto node = std::make_shared<LOD>();
    node->setName("tile lod");
    node->setCenter(model->localBound().center());
    for (std::size_t i = 0; i < lod.size(); ++i)
        node->addChild(std::make_shared<Geometry>(meshes[i]), std::isinf(lod[i].x) ? std::numeric_limits<double>::max() : lod[i].x);
    return node;
}

// Placing a scene's actor groups, group by group in scene order: one behaviour object per kind,
// made when a group first needs it (one DetourCrowd for every walker), and the actors' random
// streams numbered in that order, so that a scene places the same actors wherever it is built.
struct Placement {
    const SceneDescription& d;
    const std::string& file;
    Crowd& crowd;
    EffectCounters& effects;
    std::shared_ptr<const NavMesh> nav;  // null when no group walks or stands
    std::shared_ptr<Locomotion> walkers;
    std::shared_ptr<IdleGroups> idlers;
    std::shared_ptr<GazeLayer> walkGaze, idleGaze;
    GazeLayer::Settings gazeSettings;
    std::shared_ptr<FaceLayer> walkFace, idleFace;  // when faces, blinks or phrases are declared
    FaceLayer::Settings faceSettings;
    bool walkersOnly;  // Scope::Walkers: walkers join their Locomotion only (no layer, no crowd)
    std::uint64_t stream = 0;
    CounterRng rng;

    Placement(const SceneDescription& description, const std::string& sceneFile, Crowd& c, EffectCounters& e,
              std::shared_ptr<const NavMesh> mesh, bool walkersOnlyScope)
        : d(description), file(sceneFile), crowd(c), effects(e), nav(std::move(mesh)), walkersOnly(walkersOnlyScope),
          rng(description.seed, 0x5ce7e) {
        gazeSettings.levels = d.effects.gazeLevels;
        gazeSettings.range = d.effects.gazeRange;
        gazeSettings.seed = d.seed;
        faceSettings = d.effects.faces;
        faceSettings.seed = d.seed;
    }

    bool facesDeclared() const { return faceSettings.face || faceSettings.blink || faceSettings.phrase; }

    // The outermost layer of `base` (with its gaze layer `gaze` when declared): a face layer when
    // faces are declared (made once, into `face`), else the gaze layer, else the base.
    std::shared_ptr<Behaviour> outermost(const std::shared_ptr<Behaviour>& base, const std::shared_ptr<GazeLayer>& gaze,
                                         std::shared_ptr<FaceLayer>& face) {
        const std::shared_ptr<Behaviour> inner = gaze ? std::shared_ptr<Behaviour>(gaze) : base;
        if (!facesDeclared()) return inner;
        if (!face) face = std::make_shared<FaceLayer>(inner, faceSettings, &effects);
        return face;
    }

    // Walkways are narrow and their scenarios start people side by side: a point of the area itself,
    // onto the mesh within 10 cm (a wall's margin is no place to start), clear of everyone placed
    // before by a body's width where one of 64 tries is (else the clearest try). Those placed are
    // kept in a grid of cells a body wide, so a try looks at the 3 x 3 cells around it only.
    glm::vec3 walkwayStart(const AreaDescription& area, const CounterRng& r) {
        const float body = 2.0f * float(d.walkways->bodyRadius);
        const auto cell = [&](float x, float z) {
            return std::pair(std::int64_t(std::floor(x / body)), std::int64_t(std::floor(z / body)));
        };
        glm::vec3 best(0.0f);
        float bestClearance = -1.0f;
        for (std::uint64_t k = 0; k < 64 && bestClearance < body; ++k) {
            const glm::vec3 want(float(area.center.x + area.size.x * (r.uniform(2 * k) - 0.5)), 0.0f,
                                 float(area.center.y + area.size.y * (r.uniform(2 * k + 1) - 0.5)));
            const auto p = nav->nearestPoint(want, glm::vec3(0.1f, 1.0f, 0.1f));
            if (!p) continue;
            float clearance = body;  // nobody within a body's width: clear
            const auto [cx, cz] = cell(p->x, p->z);
            for (std::int64_t i = cx - 1; i <= cx + 1; ++i)
                for (std::int64_t j = cz - 1; j <= cz + 1; ++j)
                    if (const auto it = started.find({i, j}); it != started.end())
                        for (const glm::vec3& q : it->second) clearance = std::min(clearance, glm::length(glm::vec2(p->x - q.x, p->z - q.z)));
            if (clearance > bestClearance) best = *p, bestClearance = clearance;
        }
        if (bestClearance < 0.0f) best = nav->randomPoint(r, 64);  // no point of the area is on the mesh
        started[cell(best.x, best.z)].push_back(best);
        return best;
    }
    std::map<std::pair<std::int64_t, std::int64_t>, std::vector<glm::vec3>> started;  // walkways: who starts where, by cell

    // A random point of the navigation mesh inside `area` (or the nearest one found).
    glm::vec3 pointIn(const AreaDescription& area, std::uint64_t s) {
        const CounterRng r(d.seed, s);
        if (d.walkways) return walkwayStart(area, r);
        for (std::uint64_t k = 0; k < 64; ++k) {
            const glm::vec3 p = nav->randomPoint(r, k);
            if (std::abs(p.x - area.center.x) <= 0.5 * area.size.x && std::abs(p.z - area.center.y) <= 0.5 * area.size.y) return p;
        }
        return nav->randomPoint(r, 64);
    }

    // Walkers of group `g`, each from a random point of its area at a speed of its own.
    void walk(const ActorGroupDescription& g, const ResolvedTemplate& t, const ActorLook& look, const std::vector<double>& levels,
              std::vector<ActorId>& ids) {
        if (!walkers) {
            Locomotion::Settings s;
            s.avoidance = d.effects.avoidance;
            s.avoidanceQuality = d.effects.avoidanceQuality;
            s.avoidanceModel = d.effects.avoidanceModel == "orca" ? Locomotion::AvoidanceModel::Orca : Locomotion::AvoidanceModel::Detour;
            s.neighbourRange = static_cast<float>(d.effects.avoidanceRange);
            s.farDistance = d.effects.farUpdateDistance;
            if (d.walkways) s.radius = float(d.walkways->bodyRadius);
            s.farEvery = d.effects.farUpdateEvery;
            s.seed = d.seed;
            if (d.town) {  // walkways are one region
                s.regions = townRegions(*d.town, file);
                // Beyond 16 x 16 blocks (a tiled mesh), people walk to places within 8 blocks.
                if (std::int64_t(d.town->blocksX) * d.town->blocksZ > 256)
                    s.destinationRange = 8.0 * (d.town->blockTiles + 1) * d.town->tileSize;
            }
            walkers = std::make_shared<Locomotion>(nav, s, levels, &effects);
            if (d.effects.gaze && !walkersOnly) walkGaze = std::make_shared<GazeLayer>(walkers, gazeSettings, &effects);
        }
        const glm::dvec2 speed = g.speed.value_or(glm::dvec2(1.2, 1.6));
        const SpeedProfile* profile = g.speedProfile.empty() ? nullptr : findSpeedProfile(g.speedProfile);
        std::vector<Locomotion::Actor> group(std::size_t(g.count));
        for (Locomotion::Actor& a : group) {  // in order of stream: walkways place each clear of those before
            a.tmpl = t.tmpl;
            a.walkClip = t.walkClip;
            a.walkClipSpeed = t.walkClipSpeed;
            a.runClip = t.runClip;
            a.runClipSpeed = t.runClipSpeed;
            a.start = pointIn(g.area, stream);
            a.speed = profile ? profile->draw(rng, stream) : rng.uniform(stream, speed.x, speed.y);
            if (g.goal) a.goal = glm::vec3(float(g.goal->x), 0.0f, float(g.goal->y));
            if (g.period) a.period = glm::vec3(float(g.period->x), 0.0f, float(g.period->y));
            a.stream = stream++;
        }
        // Walkers become slots and actors in the order of where they start along a Z curve, not of
        // their streams (random places): those a view sees then lie side by side in every per-actor
        // array, so that culling and posing them reads whole cache lines instead of one walker each.
        // Each walker's randomness follows its stream, whatever its slot.
        std::stable_sort(group.begin(), group.end(), [](const Locomotion::Actor& p, const Locomotion::Actor& q) {
            return zOrder(p.start.x, p.start.z, 16.0) < zOrder(q.start.x, q.start.z, 16.0);
        });
        for (const Locomotion::Actor& a : group) {
            std::uint32_t slot = walkers->addActor(a);
            if (walkersOnly) continue;
            if (walkGaze) slot = walkGaze->wrap(slot, t.tmpl, a.stream);
            const std::shared_ptr<Behaviour> outer = outermost(walkers, walkGaze, walkFace);
            if (walkFace) {  // walkers talk in groups of consecutive streams
                const auto size = std::uint64_t(d.effects.phraseGroupSize);
                slot = walkFace->wrap(slot, t.tmpl, a.stream, a.stream / size, std::uint32_t(a.stream % size), std::uint32_t(size));
            }
            ids.push_back(crowd.add(t.tmpl, outer, slot, t.lookFor(look, a.stream)));
        }
    }

    // Standing people of group `g`, in circles of a random size facing their middle.
    void stand(const ActorGroupDescription& g, const ResolvedTemplate& t, const ActorLook& look, const std::vector<double>& levels,
               std::vector<ActorId>& ids) {
        if (!idlers) {
            idlers = std::make_shared<IdleGroups>(levels, &effects);
            if (d.effects.gaze) idleGaze = std::make_shared<GazeLayer>(idlers, gazeSettings, &effects);
        }
        const int clip = t.idleClip >= 0 ? t.idleClip : t.walkClip;
        std::int64_t placed = 0;
        while (placed < g.count) {
            const std::uint64_t groupStream = stream;
            const int size = int(std::min<std::int64_t>(g.count - placed,
                g.groupSize.x + std::int64_t(rng.below(groupStream * 7 + 1, std::uint64_t(g.groupSize.y - g.groupSize.x + 1)))));
            const glm::vec3 centre = pointIn(g.area, groupStream);
            const double radius = 0.6 + 0.45 * std::sqrt(double(size));
            for (int k = 0; k < size; ++k, ++placed, ++stream) {
                const double angle = 2.0 * std::numbers::pi * k / size + rng.uniform(stream * 3 + 2, -0.2, 0.2);
                KeyframeBehaviour::Actor a;
                a.tmpl = t.tmpl;
                a.clip = clip;
                a.position = Vec3(centre) + Vec3(radius * std::sin(angle), 0.0, radius * std::cos(angle));
                a.heading = angle + std::numbers::pi;  // facing the middle of the group
                // An idle clip plays; a walk clip is held at some instant (standing still).
                a.timeScale = t.idleClip >= 0 ? 1.0 : 0.0;
                a.timeOffset = rng.uniform(stream * 3 + 1, 0.0, t.tmpl->clips()[std::size_t(clip)]->duration());
                std::uint32_t slot = idlers->addPerson(a);
                if (idleGaze) slot = idleGaze->wrap(slot, t.tmpl, stream);
                const std::shared_ptr<Behaviour> outer = outermost(idlers, idleGaze, idleFace);
                // A standing group is a conversation: its members take turns.
                if (idleFace) slot = idleFace->wrap(slot, t.tmpl, stream, (1ull << 62) + groupStream, std::uint32_t(k), std::uint32_t(size));
                ids.push_back(crowd.add(t.tmpl, outer, slot, t.lookFor(look, stream)));
            }
        }
    }

    // Stand-ins for the actors of group `g`, which another process simulates and shows (Scope::
    // Actors): one absent actor each, numbered (and looking) as the group's own would be.
    void elsewhere(const ActorGroupDescription& g, const ResolvedTemplate& t, const ActorLook& look, const std::vector<double>& levels,
                   std::vector<ActorId>& ids) {
        auto stand = std::make_shared<ElsewhereBehaviour>(levels);
        for (std::int64_t i = 0; i < g.count; ++i, ++stream) ids.push_back(crowd.add(t.tmpl, stand, stand->addActor(), t.lookFor(look, stream)));
    }

    // A flock of its own for group `g` (the group's index `gi` seeds it).
    std::shared_ptr<Flock> fly(const ActorGroupDescription& g, std::size_t gi, const ResolvedTemplate& t, const ActorLook& look,
                               const std::vector<double>& levels, std::vector<ActorId>& ids) {
        Flock::Settings s;
        s.center = g.area.center;
        s.size = g.area.size;
        s.altitude = g.altitude;
        s.speed = g.speed.value_or(glm::dvec2(6.0, 11.0));
        s.seed = d.seed + gi;
        auto flock = std::make_shared<Flock>(s, levels, &effects);
        for (std::int64_t i = 0; i < g.count; ++i, ++stream) ids.push_back(crowd.add(t.tmpl, flock, flock->addBird({t.tmpl, t.walkClip, stream}), t.lookFor(look, stream)));
        return flock;
    }
};

// A navigation mesh's settings that a scene chooses, in words.
std::string describe(const NavMeshSettings& s) {
    char text[128];
    std::snprintf(text, sizeof text, "cell %g m, agent radius %g m, climb %g m, tiles of %g m", s.cellSize, s.agentRadius,
                  s.agentMaxClimb, s.tileSize);
    return text;
}

// A group's behaviour level bands (declared, or the default two).
std::vector<double> levelsOf(const ActorGroupDescription& g) {
    return g.levels.empty() ? std::vector<double>{60.0, std::numeric_limits<double>::infinity()} : g.levels;
}

}  // namespace

Simulation::~Simulation() = default;

const FrameContext& Simulation::step() {
    if (started_) clock_->advance();
    started_ = true;
    now_ = clock_->context();
    // Regions far from the camera (its path at this step's time) step less often when declared.
    if (walkers_ && walkers_->settings().farEvery > 1) walkers_->setViewpoint(glm::vec3(camera_->at(now_.time, 1.0).eye()));
    if (walkersOnly_) {  // a rank other than 0: its share of the walkers is all it steps
        const Stopwatch watch;
        if (walkers_) team_->run([&] { walkers_->advance(now_); });
        walkersOnlyMs_ = watch.elapsedMs();
    } else {
        team_->run([&] { crowd_.step(now_); });
    }
    return now_;
}

void Simulation::setThreads(unsigned threads) {
    if (threads == 0) throw std::invalid_argument("Simulation::setThreads: argument 'threads' must be at least 1");
    team_ = std::make_unique<ThreadTeam>(threads);
}

std::unique_ptr<Simulation> Simulation::build(SceneDescription description, const BuildProgress& progress) {
    return build(std::move(description), progress, BuildOptions{});
}

std::unique_ptr<Simulation> Simulation::build(SceneDescription description, const BuildProgress& progress, BuildOptions options) {
    std::unique_ptr<Simulation> sim(new Simulation());
    sim->description_ = std::move(description);
    sim->scope_ = options.scope;
    sim->walkersOnly_ = options.scope == Scope::Walkers;
    sim->navGiven_ = options.navMesh != nullptr;
    sim->root_ = std::make_shared<Group>();
    sim->root_->setName(sim->description_.name.empty() ? "scene" : sim->description_.name);
    const BuildProgress report = progress ? progress : [](const std::string&, double) {};
    sim->buildTown(report);
    if (const auto& town = sim->description_.town; town && town->lodScale > 0.0) sim->setTownLodScale(town->lodScale);
    sim->buildActors(report, std::move(options.navMesh));
    double extent = 100.0;
    if (sim->town_) extent = std::max(sim->town_->extent().x, sim->town_->extent().y);
    sim->camera_ = std::make_unique<CameraPath>(sim->description_.camera, extent);
    sim->clock_ = std::make_unique<SimulationClock>(sim->description_.step);
    sim->team_ = std::make_unique<ThreadTeam>(1);
    report("ready", 1.0);
    return sim;
}

void Simulation::setTownLodScale(double scale) {
    if (!(std::isfinite(scale) && scale > 0.0))
        throw std::invalid_argument("Simulation::setTownLodScale: scale must be finite and > 0, not " + std::to_string(scale));
    for (const auto& lod : townLods_) lod->setDistanceScale(scale);
    townLodScale_ = scale;
}

void Simulation::buildTown(const BuildProgress& progress) {
    const SceneDescription& d = description_;
    const std::string file = d.file.empty() ? "scene" : d.file;
    if (d.walkways) {
        // Floors to walk on, drawn as pale slabs; where there is no floor there is a wall.
        for (std::size_t i = 0; i < d.walkways->floors.size(); ++i) {
            const AreaDescription& f = d.walkways->floors[i];
            const glm::vec3 c(float(f.center.x), -0.05f, float(f.center.y)), half(float(0.5 * f.size.x), 0.05f, float(0.5 * f.size.y));
            if (scope_ == Scope::Everything) {
                auto slab = makeBox("floor " + std::to_string(i), c, half, glm::vec4(0.72f, 0.7f, 0.66f, 1.0f));
                root_->addChild(std::make_shared<Geometry>(std::make_shared<MeshDrawable>(slab)));
            }
            navGeometry_.addBox(c - glm::vec3(half.x, 0.45f, half.z), c + glm::vec3(half.x, 0.05f, half.z), true);
        }
        return;
    }
    if (!d.town) {
        // A plain ground to stand and fly over.
        if (scope_ == Scope::Everything) {
            auto ground = makeBox("ground", glm::vec3(0, -0.25f, 0), glm::vec3(250.0f, 0.25f, 250.0f), glm::vec4(0.45f, 0.5f, 0.4f, 1.0f));
            root_->addChild(std::make_shared<Geometry>(std::make_shared<MeshDrawable>(ground)));
        }
        navGeometry_.addBox(glm::vec3(-250.0f, -0.5f, -250.0f), glm::vec3(250.0f, 0.0f, 250.0f), true);
        return;
    }
    progress("laying out the town", 0.0);
    town_ = layoutTown(*d.town);
    if (scope_ != Scope::Everything && navGiven_) return;  // the layout is all a world without the town's graph needs of it then
    // One model per kind of tile, shared by every tile of that kind.
    std::map<TileKind, std::vector<std::shared_ptr<const MeshDrawable>>> models;
    for (const TilePlacement& t : town_->tiles) {
        if (models.count(t.kind)) continue;
        const std::string path = d.town->tiles + "/" + tileFile(t.kind);
        CharacterAsset asset;
        try {
            asset = loadCharacter(path);
        } catch (const std::exception& e) {
            throw SceneError(file, "/town/tiles", e.what());
        }
        auto& list = models[t.kind];
        for (const auto& p : asset.primitives) list.push_back(std::make_shared<MeshDrawable>(p.data));
        progress("loading town tiles", double(models.size()) / kTileKindCount * 0.5);
    }
    // Occluders, when the scene asks: boxes fitted inside each kind of building, once per kind.
    std::map<TileKind, std::pair<std::vector<AxisBox>, AxisBox>> occluderOf;  // boxes and shell
    if (d.town->occluders && scope_ == Scope::Everything) {
        for (const auto& [kind, list] : models) {
            if (tileWalkable(kind)) continue;
            std::vector<const MeshData*> meshes;
            AxisBox shell{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
            for (const auto& m : list) {
                meshes.push_back(&m->mesh());
                for (const glm::vec3& p : m->mesh().positions) shell.min = glm::min(shell.min, p), shell.max = glm::max(shell.max, p);
            }
            std::vector<AxisBox> boxes = fitOccluderBoxes(meshes);
            if (!boxes.empty()) occluderOf[kind] = {std::move(boxes), shell};
        }
        progress("fitting occluders", 0.5);
    }
    // Tiles grouped by chunks of 4 x 4 so that CULL rejects whole chunks (a walkers' world makes no
    // scene graph: only the tiles' surfaces for the navigation mesh).
    auto town = std::make_shared<Group>();
    town->setName("town");
    std::map<std::pair<int, int>, std::shared_ptr<Group>> chunks;
    TownLevels levels;
    for (const TilePlacement& t : town_->tiles) {
        const Mat4 m = tileTransform(*town_, t);
        for (const auto& model : models[t.kind]) navGeometry_.add(model->mesh(), glm::mat4(m), tileWalkable(t.kind));
        // Recast sees surfaces: block the inside of what stands on the tile.
        const glm::vec3 c(town_->centre(t.x, t.z));
        const float h = float(0.5 * town_->tileSize);
        if (!tileWalkable(t.kind)) navGeometry_.addBlocked(c - glm::vec3(0.47f * 2 * h, 0, 0.47f * 2 * h), c + glm::vec3(0.47f * 2 * h, 30, 0.47f * 2 * h));
        if (t.kind == TileKind::PavementFountain) navGeometry_.addBlocked(c - glm::vec3(0.3f * h, 0, 0.3f * h), c + glm::vec3(0.3f * h, 10, 0.3f * h));
        if (scope_ != Scope::Everything) continue;
        auto& chunk = chunks[{t.x / 4, t.z / 4}];
        if (!chunk) {
            chunk = std::make_shared<Group>();
            chunk->setName("chunk");
        }
        auto node = std::make_shared<Transform>();
        node->setMatrix(m);
        for (const auto& model : models[t.kind]) {
            auto tile = tileModelNode(model, d.town->lod, levels);
            if (auto lod = std::dynamic_pointer_cast<LOD>(tile)) townLods_.push_back(std::move(lod));
            node->addChild(std::move(tile));
            townTriangles_ += model->primitiveCount();
        }
        if (const auto it = occluderOf.find(t.kind); it != occluderOf.end()) {
            node->addChild(std::make_shared<Occluder>(it->second.first, it->second.second));
            effects_.constructed("occluders");
        }
        chunk->addChild(node);
    }
    for (auto& [key, chunk] : chunks) town->addChild(chunk);
    if (scope_ == Scope::Everything) root_->addChild(town);
    progress("town laid out", 0.5);
}

void Simulation::buildActors(const BuildProgress& progress, std::shared_ptr<const NavMesh> given) {
    const SceneDescription& d = description_;
    const std::string file = d.file.empty() ? "scene" : d.file;
    // A group's template copy: standing groups whose idle clip is not the walk clip get their own.
    auto copyKey = [&](const ActorGroupDescription& g) {
        const TemplateDescription& t = d.templates.at(g.templateName);
        return g.behaviour == "idle" && !t.idleClip.empty() && t.idleClip != t.walkClip ? g.templateName + "#idle" : g.templateName;
    };
    std::map<std::string, ResolvedTemplate> templates;
    for (const ActorGroupDescription& g : d.actors) {
        const std::string key = copyKey(g);
        if (g.count == 0 || templates.count(key) || (walkersOnly_ && g.behaviour != "walk")) continue;
        const ResolvedTemplate& r = templates[key] = resolve(g.templateName, d.templates.at(g.templateName), file);
        const bool standing = key != g.templateName || (g.behaviour == "idle" && r.idleClip >= 0);
        templates_.push_back({key, r.tmpl, standing && r.idleClip >= 0 ? r.idleClip : r.walkClip});
    }

    const bool anyWalk = std::any_of(d.actors.begin(), d.actors.end(), [](const auto& g) { return g.behaviour == "walk" && g.count > 0; });
    const bool anyIdle = std::any_of(d.actors.begin(), d.actors.end(), [](const auto& g) { return g.behaviour == "idle" && g.count > 0; });
    if (anyWalk || anyIdle) {
        NavMeshSettings settings;
        settings.agentMaxClimb = 0.45f;  // kerbs of the tiles at 8 m are 0.4 m
        // One Recast tile numbers its vertices with 16 bits: beyond 16 x 16 blocks, Detour tiles of
        // 2 x 2 blocks, built in parallel.
        if (d.town && std::int64_t(d.town->blocksX) * d.town->blocksZ > 256)
            settings.tileSize = float(2 * (d.town->blockTiles + 1) * d.town->tileSize);
        if (d.walkways) {
            settings.cellSize = float(d.walkways->cellSize);
            settings.agentRadius = float(d.walkways->bodyRadius);
        }
        if (given) {  // another process's (rank 0's): it must be this scene's
            if (std::memcmp(&given->settings(), &settings, sizeof settings) != 0)
                throw std::invalid_argument("Simulation::build: the navigation mesh given was built with other settings than scene '" + file +
                                            "' asks for (" + describe(given->settings()) + ", not " + describe(settings) +
                                            "): do all ranks read the same scene file?");
            nav_ = std::move(given);
        } else {
            progress("building the navigation mesh", 0.55);
            nav_ = NavMesh::build(navGeometry_, settings);
        }
    }
    navGeometry_ = NavGeometry{};

    // A rank posing the walkers it steps shows a share of them: the others' per-frame state (about
    // 1.2 KB an actor) is written only if one comes to it.
    if (scope_ == Scope::Actors) crowd_.deferStateUntilShown();
    Placement place(d, file, crowd_, effects_, nav_, walkersOnly_);
    for (std::size_t gi = 0; gi < d.actors.size(); ++gi) {
        const ActorGroupDescription& g = d.actors[gi];
        ActorGroupInfo info{g.name, g.behaviour, {}};
        if (g.count == 0) {
            groups_.push_back(info);
            continue;
        }
        if (walkersOnly_) {  // walkers join their Locomotion; the others only use up their streams
            if (g.behaviour == "walk") place.walk(g, templates.at(copyKey(g)), {}, levelsOf(g), info.actors);
            else place.stream += std::uint64_t(g.count);
            groups_.push_back(std::move(info));
            progress("placing walkers", 0.6 + 0.4 * double(gi + 1) / double(d.actors.size()));
            continue;
        }
        const ResolvedTemplate& t = templates.at(copyKey(g));
        const ActorLook look{float(g.priority), glm::vec4(1.0f), {}};
        const std::vector<double> levels = levelsOf(g);
        if (g.behaviour == "walk") place.walk(g, t, look, levels, info.actors);
        else if (scope_ == Scope::Actors) place.elsewhere(g, t, look, levels, info.actors);
        else if (g.behaviour == "idle") place.stand(g, t, look, levels, info.actors);
        else behaviours_.push_back(place.fly(g, gi, t, look, levels, info.actors));
        auto node = crowd_.makeGroupNode(info.actors);
        node->setName(g.name);
        if (g.behaviour == "walk") {
            // Walkers roam the whole mesh: their group's bound is the mesh's, whoever holds them
            // (ranks that each step some agree on it). The gather margin covers how far a Refpoint
            // Bsphere reaches from where its walker stands, and how far away (3D) anyone it may
            // look at stands.
            double reach = 0.0;
            for (ActorId id : info.actors) {
                const BoundingSphere& b = crowd_.state().refSphereLocal[id];
                reach = std::max(reach, glm::length(b.center()) + b.radius());
            }
            const auto [lo, hi] = nav_->bounds();
            const Vec3 low(lo), high(hi);
            node->setRoamingBound(BoundingSphere(0.5 * (low + high), 0.5 * glm::length(high - low) + reach + 1.0));
            const double height = high.y - low.y;
            const double gaze = place.walkGaze ? std::sqrt(place.gazeSettings.range * place.gazeSettings.range + height * height) : 0.0;
            gatherMargin_ = std::max(gatherMargin_, reach + gaze + 1.0);
            shownMargin_ = std::max(shownMargin_, reach + 1.0);
        }
        root_->addChild(node);
        groups_.push_back(std::move(info));
        progress("placing actors", 0.6 + 0.4 * double(gi + 1) / double(d.actors.size()));
    }
    walkers_ = place.walkers;
    for (const auto& b : {std::shared_ptr<Behaviour>(place.walkers), std::shared_ptr<Behaviour>(place.idlers),
                          std::shared_ptr<Behaviour>(place.walkGaze), std::shared_ptr<Behaviour>(place.idleGaze),
                          std::shared_ptr<Behaviour>(place.walkFace), std::shared_ptr<Behaviour>(place.idleFace)})
        if (b) behaviours_.push_back(b);
    for (const auto& f : {place.walkFace, place.idleFace})
        if (f) faceLayers_.push_back(f);
}

void Simulation::setGatherView(std::optional<Frustum> view) {
    if (walkers_ && walkers_->distributed()) walkers_->setGatherView(std::move(view), gatherMargin_, shownMargin_);
}

void Simulation::distribute(Ranks& ranks, bool posedWhereStepped) {
    if (started_) throw std::logic_error("Simulation::distribute: the simulation has already started");
    if (scope_ != Scope::Everything && ranks.rank() == 0)
        throw std::logic_error("Simulation::distribute: rank 0 draws and gathers, but this world was built without the town's scene graph");
    if (scope_ == Scope::Walkers && posedWhereStepped)
        throw std::logic_error("Simulation::distribute: a rank posing the walkers it steps needs their actors, but this world was built for "
                               "stepping walkers only (Scope::Actors)");
    if (!walkers_) return;
    walkers_->distribute(ranks);
    walkers_->setPosedWhereStepped(posedWhereStepped);
    // Only rank 0 draws: elsewhere the behaviours of the other actors (standing, gazing, flying)
    // would be computed for nothing. Posing where stepped, a rank steps its walkers' effects too
    // (whom they look at); the other actors stand in there and step nothing.
    walkersOnly_ = walkersOnly_ || (ranks.rank() != 0 && !posedWhereStepped);
}

void Simulation::attachKeyPoseCaches(ActorProcessor& processor) {
    const auto& declared = description_.representation.keyPoseCache;
    if (!declared) return;
    for (auto& cache : makeKeyPoseCaches()) processor.setKeyPoseCache(std::move(cache));
    processor.setKeyPoseDistance(declared->distance, description_.representation.hysteresis * declared->distance);
}

std::vector<std::shared_ptr<KeyPoseCache>> Simulation::makeKeyPoseCaches() {
    std::vector<std::shared_ptr<KeyPoseCache>> caches;
    const auto& declared = description_.representation.keyPoseCache;
    if (!declared) return caches;
    for (const TemplateInUse& t : templates_) {
        const std::string name = t.name.substr(0, t.name.find('#'));  // a standing copy shares its template's rows
        const auto rows = declared->rows.find(name);
        if (rows == declared->rows.end()) continue;
        KeyPoseCacheSettings settings;
        settings.rows = rows->second;
        settings.mode = declared->mode;
        settings.keyPosesPerSecond = declared->keyPosesPerSecond;
        try {
            caches.push_back(std::make_shared<KeyPoseCache>(t.tmpl, settings));
        } catch (const std::invalid_argument& e) {
            throw SceneError(description_.file, "/representation/keyPoseCache/rows/" + name, e.what());
        }
        effects_.constructed("key-pose cache");
    }
    return caches;
}

}  // namespace throng::sim
