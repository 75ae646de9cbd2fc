#pragma once
// --vtk: the crowd data throng-town records for ParaView, behind an interface so that a throng-town
// built without VTK (THRONG_WITH_VTK=OFF: the GPU check's bundle) still builds and says why --vtk is
// refused. VtkCrowdRecording.cpp records with throng::vtk::CrowdRecorder; NoCrowdRecording.cpp refuses.

#include <memory>
#include <string>

namespace throng {
class ActorProcessor;
class Crowd;
class Node;
}  // namespace throng

namespace throng::town {

/// Crowd data written as the run goes (see throng::vtk::CrowdRecorder for the files).
class CrowdRecording {
public:
    virtual ~CrowdRecording() = default;
    /// Writes the static scene (the town) once, after the world is built.
    virtual void writeScene(Node& root) = 0;
    /// Records the crowd after a simulation step (every K-th step is written).
    virtual void record(const Crowd& crowd, const ActorProcessor& processor) = 0;
    /// Writes what is left (trajectories, the collection file); the files are then whole.
    virtual void finish() = 0;
};

/// Opens a recording into `folder`, an actors file every `every` steps. Throws std::invalid_argument
/// for a folder that cannot be written, or when this throng-town was built without VTK.
std::unique_ptr<CrowdRecording> openCrowdRecording(const std::string& folder, int every);

}  // namespace throng::town
