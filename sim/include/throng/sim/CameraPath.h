#pragma once
// The camera a scene file describes: field of view, clip distances and a path of keys (eye and
// target) followed linearly in time and held after the last key.

#include "throng/scenegraph/Camera.h"
#include "throng/sim/SceneDescription.h"

namespace throng::sim {

/// Follows a CameraDescription.
class CameraPath {
public:
    /// The camera of `description`; with no keys, an overview of a square of side `extent` metres.
    CameraPath(CameraDescription description, double extent);
    /// The camera at `time` for a viewport of `aspect` (width / height, > 0).
    Camera at(double time, double aspect) const;
    /// Time of the last key (0 with a single key or none).
    double duration() const;

private:
    CameraDescription d_;
};

}  // namespace throng::sim
