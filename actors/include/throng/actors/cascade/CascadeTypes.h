#pragma once
// The values the actor cascade's jobs pass between them (Rodriguez et al. 2003, §4.2): where a
// candidate stands after CULL 1, what CULL 2 decided, what CULL 3 left visible, and the frame's LOD
// settings. Plain data: the jobs (one header each in this folder) read and write them.

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "throng/actors/ActorId.h"
#include "throng/actors/Affine.h"
#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/KeyPoseSource.h"

namespace throng {

class ActorTemplate;
class Drawable;
class KeyPoseCache;
class Node;

namespace cascade {

/// Elements per chunk of the light per-actor loops (Reference Points, Skeleton Roots, CULL 1 and 2).
inline constexpr std::size_t kLightGrain = 512;
/// Elements per chunk of the heavy ones (poses, CULL 3, draw items).
inline constexpr std::size_t kHeavyGrain = 64;

/// Where a candidate stands after CULL 1.
enum Stage : std::uint8_t {
    kPending = 0,   ///< a group member whose Refpoint Bsphere is still to be tested
    kInside = 1,    ///< Refpoint Bsphere inside every plane
    kCrossing = 2,  ///< Refpoint Bsphere crosses a plane
    kOutside = 3,   ///< rejected by CULL 1
};

/// What CULL 2 decided for a survivor of CULL 1.
enum Outcome : std::uint8_t {
    kRejected = 0,  ///< Sklsroot Bsphere outside (C1), or hidden
    kPosed = 1,     ///< goes on to phases 5-7 with its geometry
    kImpostor = 2,  ///< drawn as an impostor; no Skeleton node processed
    kCached = 3,    ///< in a key-pose cache's band: drawn from the cache if its poses are held
};

/// Which parts of a posed actor CULL 3 left visible.
enum Visibility : std::uint8_t {
    kNoneVisible = 0,  ///< none: the whole internal bound was outside
    kAllVisible = 1,   ///< all: the Sklsroot Bsphere or the whole internal bound was inside
    kPerPart = 2,      ///< decided part by part (C3.2)
};

/// Plane mask of a node whose subtree sphere was found outside.
inline constexpr PlaneMask kCulled = 0xFF;

/// One actor reaching CULL 1, and what the cascade found.
struct Candidate {
    ActorId id;              ///< the actor
    const Node* node;        ///< the node holding it
    std::uint32_t member;    ///< its index in that node
    PlaneMask mask;          ///< planes still crossed after the last test
    std::uint8_t stage;      ///< a Stage
};

/// The level-of-detail settings a frame runs with (the processor's, see ActorProcessor).
struct Settings {
    double lodScale2 = 1.0;                 ///< LOD scale squared
    bool skeletalLod = true;                ///< deactivate Skeleton nodes by distance
    bool behaviouralLod = true;             ///< behaviours run at their distance level
    double impostorDistance = 0.0;          ///< 0: no impostors
    double impostorHysteresis = 0.0;        ///< metres either side of the distance
    /// Impostor drawable of each template that has one (null: none).
    const std::vector<std::pair<const ActorTemplate*, std::shared_ptr<const Drawable>>>* impostors = nullptr;
    double keyPoseDistance = 0.0;           ///< start of the key-pose band (0: no caches)
    double keyPoseHysteresis = 0.0;         ///< metres either side of it
    /// Key-pose cache of each template that has one (null: none).
    const std::vector<std::shared_ptr<KeyPoseCache>>* keyPoseCaches = nullptr;

    /// True when actors may become impostors this frame.
    bool impostorsOn() const { return impostorDistance > 0.0 && impostors; }
    /// True when key-pose caches take part this frame.
    bool keyPoseCachesOn() const { return keyPoseDistance > 0.0 && keyPoseCaches && !keyPoseCaches->empty(); }
};

/// CULL 2's decisions, one entry per survivor of CULL 1 (phase 4; key-pose selection may turn a
/// kCached actor into a kPosed one).
struct SurvivorDecisions {
    std::vector<std::uint8_t> outcome;    ///< an Outcome
    std::vector<double> detail2;          ///< squared detail distance (unless rejected)
    std::vector<int> level;               ///< behavioural level (kPosed and kCached)
    std::vector<std::uint16_t> cacheOf;   ///< index in Settings::keyPoseCaches (kCached; sized only with caches)
    std::vector<KeyPoseRef> keyPoseOf;    ///< poses needed, then the rows holding them (kCached; idem)
};

/// The actors shown this frame in candidate order and, for the posed ones, their Skeleton nodes
/// (phase 4's skeletal LOD; model matrices and counts from phase 5).
struct PosedActors {
    /// Marks a shown actor that is not posed.
    static constexpr std::uint32_t kNotPosed = ~std::uint32_t{0};
    std::vector<std::uint32_t> shown;     ///< survivor indices not rejected by CULL 2
    std::vector<std::uint32_t> posedOf;   ///< per shown actor: its index among the posed, or kNotPosed
    std::vector<std::uint32_t> posed;     ///< survivor indices of the posed actors
    std::vector<int> level;               ///< per posed: behavioural level
    std::vector<std::uint32_t> nodeBase;  ///< per posed: its first entry in the per-node arrays
    std::vector<std::uint8_t> active;     ///< per node of each posed actor: kept by skeletal LOD
    std::vector<Affine> model;            ///< per node: node to Skeleton Root (phase 5)
    std::vector<std::uint32_t> evaluated; ///< per posed: Skeleton nodes evaluated (phase 5)
};

/// What CULL 3 left visible, per posed actor and per node of each (phase 6).
struct InternalVisibility {
    std::vector<std::uint8_t> visibility;   ///< per posed: a Visibility
    std::vector<std::uint8_t> rootVisible;  ///< per posed: its actor-level geometry is visible
    std::vector<std::uint8_t> visible;      ///< per node: its geometry is visible
    std::vector<BoundingSphere> geometry;   ///< per node: geometry sphere, Skeleton Root frame
    std::vector<BoundingSphere> subtree;    ///< per node: subtree sphere, Skeleton Root frame
    std::vector<PlaneMask> masks;           ///< per node: planes still crossed (kCulled: outside)
};

/// Throws std::invalid_argument "`job`: `problem`" when `problem` is not null (a job that cannot run).
void throwIfInvalid(const char* job, const char* problem);

}  // namespace cascade
}  // namespace throng
