#pragma once
// The example scene of the cost model (seed 002 Tables 2 and 3), built relative to a camera: actors
// of the Table 3 template placed so that exactly the requested numbers fall in each class of the
// culling cascade (A, B, C1, C2, C3.1, C3.2) at the given time. Scaled counts keep the proportions
// for larger scenes.

#include <array>
#include <memory>
#include <vector>

#include "throng/actors/ActorId.h"
#include "throng/actors/Crowd.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"

namespace throng {

class KeyframeBehaviour;

/// How many actors of each class (Table 2: 20, 30, 20, 20, 8, 2).
struct CascadeCounts {
    std::size_t a = 20;     ///< Refpoint Bsphere outside
    std::size_t b = 30;     ///< Refpoint Bsphere inside
    std::size_t c1 = 20;    ///< Sklsroot Bsphere outside
    std::size_t c2 = 20;    ///< Sklsroot Bsphere inside
    std::size_t c3_1 = 8;   ///< internal spheres wholly in or out
    std::size_t c3_2 = 2;   ///< internal spheres culled one by one

    /// Total actors.
    std::size_t total() const { return a + b + c1 + c2 + c3_1 + c3_2; }
    /// Table 2's proportions for `actors` actors (rounded; the total is exact).
    static CascadeCounts scaled(std::size_t actors);
};

/// What to build.
struct CostModelSceneOptions {
    CascadeCounts counts;               ///< actors per class
    bool group = false;                 ///< one ActorGroup node for all (else one Actor node each)
    std::uint64_t seed = 1;             ///< placement along the frustum edge
    double nearDepth = 80.0;            ///< actors stand between these depths in front of the camera,
    double farDepth = 200.0;            ///< beyond the template's half-detail distance (fLODtopo 0.5)
    Vec3 origin{0.0};                   ///< where the camera stands (to test far from the world origin)
};

/// The scene and how to look at it.
struct CostModelScene {
    std::shared_ptr<Group> root;                 ///< holds the actor nodes
    Camera camera;                               ///< the camera the classes are relative to
    double time = 0.0;                           ///< the frame time the classes hold at
    std::array<std::vector<ActorId>, 6> byClass; ///< actors of A, B, C1, C2, C3.1, C3.2
};

/// Adds the scene's actors to `crowd` (Table 3 template, playing its clip with `behaviour`) and
/// builds the scene. Throws std::invalid_argument if the template cannot be placed (its Sklsroot
/// margin leaves no room between the classes) or the depths are not ordered.
CostModelScene buildCostModelScene(Crowd& crowd, std::shared_ptr<const ActorTemplate> tmpl,
                                   std::shared_ptr<KeyframeBehaviour> behaviour, const CostModelSceneOptions& options = {});

/// The Table 2 layout scaled to `actors` (CascadeCounts::scaled), every actor of the Table 3 template
/// playing its keyframes in one ActorGroup: the scene bench_actor_processing, the OpenSceneGraph
/// peer, throng-costmodel and the steady-frame test measure.
CostModelScene buildTable2Scene(Crowd& crowd, std::size_t actors);

}  // namespace throng
