#pragma once
// The two scenes bench_actor_processing measures, built the same way for the OpenSceneGraph
// comparison: Table 2's proportions (the cost model's Table 3 actors placed class by class relative
// to a camera) and a town-like spread of walking seed humanoids, one actor group per block; and,
// for the visibility check, the town spread 100 times as dense and seen between near and far planes
// at 5 m and 60 m, where many actors stand near a frustum plane or an LOD threshold.

#include <memory>
#include <string>

#include "throng/actors/Crowd.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"

namespace throng::peers {

/// A scene, its camera and the time of each measured frame.
struct PeerScene {
    std::string name;                                         ///< "table2", "town" or "town-dense"
    std::unique_ptr<Crowd> crowd = std::make_unique<Crowd>();  ///< the actors' state
    std::shared_ptr<Group> root;                              ///< one ActorGroup node, or one per block
    Camera camera;                                            ///< fixed for every frame
    double startTime = 0.0;                                   ///< time of frame 0
    /// Table 2's classes hold only at the scene's own time, so its frames alternate between that
    /// time and 1 ns later (a key time: both behaviour levels agree); the town plays at 60 Hz.
    bool holdTime = false;

    /// Time of frame `frame`.
    double timeOf(std::size_t frame) const {
        return holdTime ? startTime + double(frame % 2) * 1e-9 : startTime + double(frame) / 60.0;
    }
};

/// Builds scene `name` ("table2", "town" or "town-dense") with `actors` actors. Throws
/// std::invalid_argument for another name or zero actors.
PeerScene buildPeerScene(const std::string& name, std::size_t actors);

}  // namespace throng::peers
