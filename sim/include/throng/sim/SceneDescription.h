#pragma once
// What a scene file declares (JSON; see SceneParser): the town, actor templates, groups of actors
// with their behaviour and its levels of detail, effects, representation distances and the camera
// path. Only what is declared here is ever constructed.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "throng/actors/KeyPoseCache.h"
#include "throng/scenegraph/BodyLook.h"
#include "throng/scenegraph/OcclusionCulling.h"
#include "throng/sim/FaceLayer.h"

namespace throng::sim {

/// A region of the town: the blocks [from, to) across (x) and deep (z).
struct RegionRectangle {
    glm::ivec2 from{0};  ///< first block (x, z)
    glm::ivec2 to{1};    ///< one past the last block (x, z)
};

/// The town the actors walk in.
struct TownDescription {
    int blocksX = 5;            ///< city blocks across
    int blocksZ = 5;            ///< city blocks deep
    int blockTiles = 3;         ///< tiles per block side (between roads)
    double tileSize = 8.0;      ///< metres per tile
    std::uint64_t seed = 1;     ///< layout
    std::string tiles;          ///< folder of the tile models (relative to the scene file)
    bool occluders = false;     ///< buildings get occluder boxes fitted inside them (for occlusion culling)
    /// Geometric levels of every tile model {until distance from the tile's centre, share of
    /// triangles}, nearest first, as for templates; the last may reach to any distance. Empty: no
    /// town LOD (the full tiles everywhere, nothing simplified).
    std::vector<glm::dvec2> lod;
    /// Multiplies the town's LOD distances on top of the LOD scale (Simulation::setTownLodScale);
    /// 0: not set (1). A small value keeps declared levels unused until a frame budget asks for
    /// them: the town is built with its levels and drawn at full detail.
    double lodScale = 0.0;
    /// Regions stepped apart: rectangles of `regionBlocks` blocks (the last row and column may be
    /// smaller), unless `regions` lists them; together they must cover every block once.
    glm::ivec2 regionBlocks{4, 4};
    std::vector<RegionRectangle> regions;  ///< explicit rectangles, or empty
};

/// An actor template: a glTF file, or a procedural one ("seed-humanoid", "table3", "bird").
struct TemplateDescription {
    std::string gltf;           ///< path (relative to the scene file), or empty
    std::string procedural;     ///< name, or empty
    std::string walkClip;       ///< clip to walk with (default: the first)
    std::string runClip;        ///< clip to run with, or empty
    std::string idleClip;       ///< clip to stand with, or empty (walk clip held)
    double walkClipSpeed = 1.4; ///< speed the walk clip was authored for, m/s
    double runClipSpeed = 3.5;  ///< speed the run clip was authored for, m/s
    double scale = 1.0;         ///< glTF: uniform scale to metres (Fox: 0.01)
    /// glTF: geometric levels {until distance, share of triangles}, nearest first; the last one
    /// may reach to infinity. Empty: the full mesh at every distance.
    std::vector<glm::dvec2> lod;
    double jointMinAngle = 0.0; ///< glTF: skeletal LOD, joints off below this angle (radians; 0: off)
    /// glTF: crowd diversity, the looks its actors wear (each actor one, hashed from its group and
    /// index); empty: every actor as modelled. Non-empty gives the mesh body regions.
    std::vector<BodyLook> looks;
};

/// Where a group of actors starts: a rectangle on the ground (centre and size, metres).
struct AreaDescription {
    glm::dvec2 center{0.0};  ///< centre (x, z), metres
    glm::dvec2 size{100.0};  ///< extent across (x) and deep (z), metres
};

/// Walkways instead of a town: rectangles of flat floor people may walk on, everything else a
/// wall. Corridors, corners and bottlenecks, as pedestrian-dynamics validation scenarios draw them.
struct WalkwaysDescription {
    std::vector<AreaDescription> floors;  ///< walkable rectangles (centre and size, metres), overlapping or touching
    double cellSize = 0.1;                ///< navigation mesh voxel across, metres (fine enough for narrow doors)
    double bodyRadius = 0.35;             ///< the walkers' radius, metres: kept from walls and from each other
};

/// A group of actors sharing a template and a behaviour.
struct ActorGroupDescription {
    std::string name;                    ///< for statistics ("group 0" if not given)
    std::string templateName;            ///< key into SceneDescription::templates
    std::int64_t count = 0;              ///< how many
    std::string behaviour;               ///< "walk", "idle" or "flight"
    AreaDescription area;                ///< where they start
    std::optional<glm::dvec2> speed;     ///< walk: preferred speed range (default 1.2-1.6 m/s); flight: airspeed (6-11)
    glm::dvec2 altitude{25.0, 40.0};     ///< flight: height range, m
    glm::ivec2 groupSize{3, 5};          ///< idle: people per group
    std::vector<double> levels;          ///< behavioural LOD bands (ends, metres); empty: defaults
    double priority = 1.0;               ///< detail priority
    /// walk: a fixed destination (x, z), walked to and stayed at; none: random destinations.
    std::optional<glm::dvec2> goal;
    /// walk, with a goal, on walkways: a periodic corridor; a walker within 1 m of the line through
    /// the goal across this vector (x, z) re-enters this far back (Locomotion::Actor::period).
    std::optional<glm::dvec2> period;
    /// walk: free speeds drawn from a named table of measured people instead of `speed` (see
    /// speedProfile(): "rimea-under-30", "rimea-30-to-50", "rimea-over-50", "rimea-impaired").
    std::string speedProfile;
};

/// Effects that exist only when declared.
struct EffectsDescription {
    bool avoidance = false;                ///< local avoidance between walkers
    std::string avoidanceModel = "detour"; ///< what keeps walkers apart: "detour" (DetourCrowd) or "orca"
    int avoidanceQuality = 3;              ///< DetourCrowd's velocity sampling, 0 (coarsest) to 3 (finest)
    double avoidanceRange = 12.0;          ///< how far walkers look for neighbours, agent radii
    double farUpdateDistance = 0.0;        ///< walkers' regions farther than this from the camera step less often (0: never)
    int farUpdateEvery = 1;                ///< how often those far regions step: every N steps
    bool gaze = false;                     ///< heads and necks turn to look at things
    std::vector<double> gazeLevels{12.0, 40.0};  ///< gaze bands: eyes-and-neck precise, then neck only
    double gazeRange = 10.0;               ///< how far people notice others, m
    /// Faces: expressions, blinks and phrases, each on only where declared (faces.face,
    /// faces.blink, faces.phrase), with their bands and settings (the seed is the scene's).
    FaceLayer::Settings faces;
    int phraseGroupSize = 3;               ///< walkers take turns speaking in groups of this many (standing groups are their own)
};

/// A key of the camera path.
struct CameraKey {
    double time = 0.0;                     ///< seconds
    glm::dvec3 eye{0.0, 30.0, 60.0};       ///< position
    glm::dvec3 target{0.0};                ///< looked-at point
};

/// The camera.
struct CameraDescription {
    double fovDegrees = 60.0;              ///< vertical field of view, degrees (below 180)
    double nearDistance = 0.1;             ///< near clipping distance, metres
    double farDistance = 1500.0;           ///< far clipping distance, metres (beyond near)
    std::vector<CameraKey> path;           ///< keys in time order (linear between them; held after the last)
};

/// Key-pose caches (seed 004): skinned key-poses shared by the actors of a middle band.
struct KeyPoseCacheDescription {
    double distance = 15.0;                 ///< the band starts here (metres; impostors end it)
    KeyPoseMode mode = KeyPoseMode::Intermittent;  ///< nearest key-pose, or a blend of two
    double keyPosesPerSecond = 15.0;        ///< key-poses per second of clip
    std::map<std::string, std::uint32_t> rows;  ///< rows per template name (only these get a cache)
};

/// How an impostor shows an eye between its baked views (seed 003 §4.1).
enum class ImpostorViews : std::uint8_t {
    Blend,    ///< the three views around the eye, by its barycentric weights clamped to their cell
    Nearest,  ///< the nearest view alone (snapping: cheaper, pops as the eye moves)
    Warped,   ///< the figure's surface proxy per impostor, at its clip time from the real eye, textured from the three views
};

/// How much of each impostor atlas is kept; the rest is regenerated when drawn (seed 000 §5).
enum class ImpostorAtlasStorage : std::uint8_t {
    Full,           ///< every key-frame of every view
    HalfKeyframes,  ///< every other key-frame
    Half,           ///< every other key-frame and every other view ring (a quarter of the texture)
};

/// Distances choosing how actors are drawn.
struct RepresentationDescription {
    double impostorDistance = 0.0;         ///< beyond it, impostors (0: never)
    ImpostorViews impostorViews = ImpostorViews::Blend;  ///< how impostors show eyes between views
    bool impostorSmoothstep = false;       ///< Blend: weights through the quintic smoothstep, renormalised (sharper)
    ImpostorAtlasStorage impostorAtlas = ImpostorAtlasStorage::HalfKeyframes;  ///< what the atlases keep
    double hysteresis = 0.1;               ///< fraction of the distance kept before switching back
    double lodScale = 1.0;                 ///< multiplies every LOD distance
    /// Occlusion culling against the scene's occluders with this buffer; none: off, nothing built.
    std::optional<OcclusionSettings> occlusion;
    /// Key-pose caches for the templates named; none: no cache built, no band.
    std::optional<KeyPoseCacheDescription> keyPoseCache;
};

/// A whole scene.
struct SceneDescription {
    std::string name;                                      ///< root node's name ("scene" if empty)
    std::uint64_t seed = 1;                                ///< actors' randomness (not the town's)
    double step = 1.0 / 60.0;                              ///< simulation step, seconds
    std::optional<TownDescription> town;                   ///< none: walkways, or else a flat ground
    std::optional<WalkwaysDescription> walkways;           ///< instead of a town: walkable floors
    std::map<std::string, TemplateDescription> templates;  ///< actor templates by name
    std::vector<ActorGroupDescription> actors;             ///< groups of actors, in file order
    EffectsDescription effects;                            ///< declared effects (none by default)
    RepresentationDescription representation;              ///< how actors are drawn with distance
    CameraDescription camera;                              ///< the camera and its path
    std::string baseDirectory;                             ///< paths in the file are relative to it
    std::string file;                                      ///< where it was read from, for messages
};

}  // namespace throng::sim
