#pragma once
// Reading back what throng::vtk wrote, with VTK's own readers (the files are checked by the library
// ParaView uses, not by the code that wrote them).

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <vtkAbstractArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUtilities.h>

namespace throng::testkit {

/// The poly data in `path`, read by vtkXMLPolyDataReader; fails the test (null) if it cannot be read.
inline vtkSmartPointer<vtkPolyData> readPolyData(const std::filesystem::path& path) {
    auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    if (!reader->CanReadFile(path.c_str())) {
        ADD_FAILURE() << "VTK cannot read " << path;
        return nullptr;
    }
    reader->SetFileName(path.c_str());
    reader->Update();
    EXPECT_EQ(reader->GetErrorCode(), 0u) << path;
    return reader->GetOutput();
}

/// The values of point-data array `name` as doubles (empty, and a failure, if it is missing).
inline std::vector<double> pointValues(vtkPolyData& data, const char* name) {
    vtkDataArray* a = data.GetPointData()->GetArray(name);
    if (!a) {
        ADD_FAILURE() << "no point-data array '" << name << "'";
        return {};
    }
    std::vector<double> v(static_cast<std::size_t>(a->GetNumberOfTuples()));
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = a->GetComponent(static_cast<vtkIdType>(i), 0);
    return v;
}

/// One entry of a .pvd collection.
struct PvdEntry {
    double time;       ///< timestep attribute
    std::string file;  ///< file attribute
};

/// The entries of the .pvd collection in `path`, parsed by VTK's XML parser.
inline std::vector<PvdEntry> readPvd(const std::filesystem::path& path) {
    std::vector<PvdEntry> entries;
    vtkXMLDataElement* root = vtkXMLUtilities::ReadElementFromFile(path.c_str());
    if (!root) {
        ADD_FAILURE() << "VTK cannot parse " << path;
        return entries;
    }
    EXPECT_STREQ(root->GetName(), "VTKFile");
    EXPECT_STREQ(root->GetAttribute("type"), "Collection");
    vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
    EXPECT_NE(collection, nullptr);
    for (int i = 0; collection && i < collection->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement* e = collection->GetNestedElement(i);
        double t = -1.0;
        e->GetScalarAttribute("timestep", t);
        entries.push_back({t, e->GetAttribute("file") ? e->GetAttribute("file") : ""});
    }
    root->Delete();
    return entries;
}

}  // namespace throng::testkit
