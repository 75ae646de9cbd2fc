// --vtk through VTK's XML writers (throng::vtk::CrowdRecorder).
#include "CrowdRecording.h"

#include "throng/vtk/CrowdRecorder.h"

namespace throng::town {

namespace {

class VtkCrowdRecording final : public CrowdRecording {
public:
    VtkCrowdRecording(const std::string& folder, int every) : recorder_(folder, every) {}
    void writeScene(Node& root) override { recorder_.writeScene(root); }
    void record(const Crowd& crowd, const ActorProcessor& processor) override { recorder_.record(crowd, processor); }
    void finish() override { recorder_.finish(); }

private:
    vtk::CrowdRecorder recorder_;
};

}  // namespace

std::unique_ptr<CrowdRecording> openCrowdRecording(const std::string& folder, int every) {
    return std::make_unique<VtkCrowdRecording>(folder, every);
}

}  // namespace throng::town
