#include "throng/vtk/CameraCascade.h"

#include <stdexcept>
#include <string>

#include <vtkRenderer.h>

#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/vtk/CameraFromVtk.h"

namespace throng::vtk {

CameraCascade::CameraCascade(Crowd* crowd, Node* root, const char* who) : crowd_(crowd), root_(root) {
    if (!crowd || !root) throw std::invalid_argument(std::string(who) + ": the crowd and the scene root are required");
    processor_ = std::make_unique<ActorProcessor>(*crowd);
}

CameraCascade::~CameraCascade() = default;

const ActorFrameStatistics& CameraCascade::run(vtkRenderer& renderer) {
    camera_ = cameraFromVtk(*renderer.GetActiveCamera(), renderer.GetTiledAspectRatio());
    return processor_->processFrame(*root_, camera_, crowd_->time());
}

}  // namespace throng::vtk
