#pragma once
// Crowd data for ParaView: every K simulation steps a VTK XML PolyData file of the actors (one point
// per actor at its Reference Point, with what the frame made of it), the scene's static geometry
// once, the actors' trajectories as polylines at the end, and a .pvd collection that ParaView opens
// as a time series. The files are written with VTK's XML writer (binary, appended, zlib).
//
//   DIR/actors_NNNNNN.vtp  NNNNNN = simulation step; point data (one value per actor):
//       id               the actor's ActorId
//       group            index of the scenegraph node holding it (names: field data group_names), -1 none
//       template         index of its template (names: field data template_names)
//       tier             how it was drawn: -1 not drawn, 0 mesh, 1 key-pose cache, 2 impostor
//       lod              vaLod level of the geometry drawn (0 highest), -1 not drawn or an impostor
//       behaviour_level  the behaviour's level it was posed at, -1 not posed this frame
//       speed            m/s of its Reference Point over the step before (from the last positions
//                        kept, when that step was not recorded; 0 on the first)
//       cascade_class    its class in the culling cascade (seed 002 Table 2; names: class_names),
//                        -1 under traditional processing (no cascade)
//       rejected_at      the phase that rejected it: 0 none (drawn), 1 with its generic group,
//                        2 CULL 1 (Refpoint Bsphere), 3 CULL 2 (Sklsroot Bsphere), 4 occlusion,
//                        5 CULL 3 (no part visible), 6 not in the scene (names: rejected_at_names);
//                        -1 under traditional processing
//     field data TimeValue (simulation seconds) and step.
//   DIR/town.vtp           writeScene(): the scene's triangles (scenePolyData)
//   DIR/trajectories.vtp   finish(): one polyline per actor through its recorded positions (one
//                          recorded position: a line from it to itself); point data time and
//                          speed, cell data id, group, template
//   DIR/crowd.pvd          finish(): the actors files with their times
//   DIR/crowd_maps.vti, density.png, speed.png, speed_density.csv
//                          finish(): where the recorded actors went, how fast, and how fast at
//                          each local density (CrowdMaps.h)

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

class vtkPolyData;

namespace throng {
class ActorProcessor;
class Crowd;
class Node;
}  // namespace throng

namespace throng::vtk {

/// Writes a crowd's frames, scene and trajectories for ParaView.
class CrowdRecorder {
public:
    /// Records into `directory` (created with its parents) every `every` steps. Throws
    /// std::invalid_argument naming the problem when `every` < 1 or the directory cannot be
    /// created or written (a file in the way, no permission), before anything is recorded.
    CrowdRecorder(std::filesystem::path directory, int every);
    /// Finishes (trajectories, .pvd) if finish() was not called; an error is reported on stderr.
    ~CrowdRecorder();
    CrowdRecorder(const CrowdRecorder&) = delete;
    CrowdRecorder& operator=(const CrowdRecorder&) = delete;

    /// Writes the static geometry under `root` (every mesh leaf, actors left out) to town.vtp.
    /// Throws std::runtime_error naming the file if it cannot be written.
    void writeScene(Node& root);
    /// Records the frame `processor` just processed for `crowd` (call it after processFrame, once
    /// per simulation step; a second call for the same step is ignored): keeps the positions it
    /// needs for speeds and trajectories and, on every `every`-th step (step 0 included), writes
    /// actors_NNNNNN.vtp. Throws std::runtime_error naming the file if it cannot be written.
    void record(const Crowd& crowd, const ActorProcessor& processor);
    /// Writes trajectories.vtp, crowd.pvd and the crowd maps (later records are refused). Throws std::runtime_error
    /// naming the file if one cannot be written.
    void finish();

    /// The folder written to.
    const std::filesystem::path& directory() const { return directory_; }
    /// Steps between two actors files.
    int every() const { return every_; }
    /// Actors files written so far.
    std::size_t framesWritten() const { return frames_.size(); }

private:
    struct WrittenFrame {
        std::int64_t step;     // simulation step
        double time;           // simulation seconds
        std::string file;      // name inside the directory
        std::size_t actors;    // actors (points) in it
        std::size_t offset;    // first of its positions in samples_ (3 values per actor)
    };
    void writeFrame(const Crowd& crowd, const ActorProcessor& processor, std::int64_t step, double time);
    void writeTrajectories();
    void writeCollection() const;
    void write(vtkPolyData& data, const std::string& name) const;

    std::filesystem::path directory_;
    int every_;
    bool finished_ = false;
    std::int64_t lastStep_ = -1;             // last step recorded
    double lastTime_ = 0.0;                  // its time
    std::vector<double> last_;               // Reference Point positions at lastStep_, x y z per actor
    std::vector<WrittenFrame> frames_;       // the actors files written, in order
    std::vector<double> samples_;            // positions of every written frame, x y z per actor
    std::vector<double> sampleSpeed_;        // speed of every written frame, per actor
    std::vector<int> groupOf_, templateOf_;  // per actor of the last written frame (trajectories' cell data)
    std::vector<std::string> groupNames_, templateNames_;
    // Per written frame: per-actor values, reused from frame to frame.
    std::vector<std::int8_t> tier_;
    std::vector<int> lod_;
};

}  // namespace throng::vtk
