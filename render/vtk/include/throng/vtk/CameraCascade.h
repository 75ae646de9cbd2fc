#pragma once
// The actor cascade of one crowd's scene, run for a VTK renderer's active camera: what the VTK
// classes that cull or draw a crowd (CascadeCuller, CrowdProp) share.

#include <memory>

#include "throng/actors/ActorFrameStatistics.h"
#include "throng/scenegraph/Camera.h"

class vtkRenderer;

namespace throng {
class ActorProcessor;
class Crowd;
class Node;
}  // namespace throng

namespace throng::vtk {

/// An ActorProcessor over a crowd's scene, fed VTK's camera.
class CameraCascade {
public:
    /// Processes the actors of `crowd` held by nodes under `root` (both must outlive it). Throws
    /// std::invalid_argument naming `who` (the caller) if either is null.
    CameraCascade(Crowd* crowd, Node* root, const char* who);
    ~CameraCascade();
    CameraCascade(const CameraCascade&) = delete;
    CameraCascade& operator=(const CameraCascade&) = delete;

    /// Runs the cascade for `renderer`'s active camera (cameraFromVtk, the renderer's tiled aspect
    /// ratio) at the crowd's time; its draw list is then the processor's.
    const ActorFrameStatistics& run(vtkRenderer& renderer);
    /// The crowd.
    Crowd& crowd() const { return *crowd_; }
    /// The processor (its settings are the application's to choose).
    ActorProcessor& processor() const { return *processor_; }
    /// The camera of the last run().
    const Camera& camera() const { return camera_; }

private:
    Crowd* crowd_;
    Node* root_;
    std::unique_ptr<ActorProcessor> processor_;
    Camera camera_;
};

}  // namespace throng::vtk
