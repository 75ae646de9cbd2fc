// --vtk in a throng-town built without VTK (THRONG_WITH_VTK=OFF): refused, saying why.
#include "CrowdRecording.h"

#include <stdexcept>

namespace throng::town {

std::unique_ptr<CrowdRecording> openCrowdRecording(const std::string&, int) {
    throw std::invalid_argument("this throng-town was built without VTK (THRONG_WITH_VTK=OFF): no ParaView files");
}

}  // namespace throng::town
