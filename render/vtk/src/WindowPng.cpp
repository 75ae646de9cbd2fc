#include "throng/vtk/WindowPng.h"

#include <filesystem>
#include <stdexcept>

#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

namespace throng::vtk {

void writeWindowPng(vtkRenderWindow& window, const std::string& path) {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(&window);
    grab->ReadFrontBufferOff();
    grab->Update();
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputConnection(grab->GetOutputPort());
    writer->Write();
    std::error_code ec;
    if (writer->GetErrorCode() != 0 || !std::filesystem::exists(path, ec) || std::filesystem::file_size(path, ec) == 0)
        throw std::runtime_error("could not write the PNG '" + path + "'");
}

}  // namespace throng::vtk
