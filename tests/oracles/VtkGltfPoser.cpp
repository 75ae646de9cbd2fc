#include "VtkGltfPoser.h"

#include <filesystem>
#include <stdexcept>

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataObjectTreeIterator.h>
#include <vtkExecutive.h>
#include <vtkGLTFReader.h>
#include <vtkIdList.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

namespace throng::test {
namespace {

// Counts the errors a VTK object reports, so that a failed read is an exception, not a silent
// empty mesh.
void countErrors(vtkObject* caller, unsigned long, void* clientData, void*) {
    (void)caller;
    ++*static_cast<int*>(clientData);
}

// vtkGLTFReader keeps its output blocks from one update to the next and, on every update after
// the first, writes each primitive of a mesh into the mesh's first block (its primitive loop never
// advances the block index): a mesh of several primitives (the robot's hands and head) comes out
// wrong from the second time step on. Each update here starts from an empty output, as the first.
class FreshOutputGltfReader : public vtkGLTFReader {
public:
    static FreshOutputGltfReader* New();
    vtkTypeMacro(FreshOutputGltfReader, vtkGLTFReader)

protected:
    int RequestData(vtkInformation* request, vtkInformationVector** in, vtkInformationVector* out) override {
        this->OutputDataSet = nullptr;
        return vtkGLTFReader::RequestData(request, in, out);
    }
};
vtkStandardNewMacro(FreshOutputGltfReader)

vtkSmartPointer<vtkGLTFReader> openReader(const std::string& path) {
    vtkSmartPointer<vtkGLTFReader> reader = vtkSmartPointer<FreshOutputGltfReader>::New();
    reader->SetFileName(path.c_str());
    // TIME_STEPS are advertised at this rate; UPDATE_TIME_STEP may ask for any time in between
    // (the reader samples the animation at the requested time itself).
    reader->SetFrameRate(60);
    if (!reader->GetExecutive()->UpdateInformation() || reader->GetNumberOfScenes() < 1)
        throw std::runtime_error(path + ": vtkGLTFReader could not read the file");
    return reader;
}

}  // namespace

// Given a path that is not collapsed ("a/../b", as the shared assets' path is), vtkGLTFReader 9.1
// applies no animation: every pose comes out at rest (measured). Its RequestInformation replaces
// the name by the collapsed path, which, by its source, makes it reload the metadata and rebuild
// the animation selection with every animation disabled. Hence the canonical path.
VtkGltfPoser::VtkGltfPoser(const std::string& path)
    : path_(std::filesystem::weakly_canonical(path).string()), info_(openReader(path_)) {}

VtkGltfPoser::~VtkGltfPoser() = default;

int VtkGltfPoser::animationCount() const { return static_cast<int>(info_->GetNumberOfAnimations()); }

int VtkGltfPoser::findAnimation(const std::string& name) const {
    for (int a = 0; a < animationCount(); ++a)
        if (info_->GetAnimationName(a) == name) return a;
    return -1;
}

double VtkGltfPoser::duration(int a) const { return info_->GetAnimationDuration(a); }

vtkGLTFReader& VtkGltfPoser::reader(int a) {
    auto it = readers_.find(a);
    if (it == readers_.end()) {
        auto r = openReader(path_);
        if (a >= 0) {
            if (a >= r->GetNumberOfAnimations())
                throw std::runtime_error(path_ + ": no animation " + std::to_string(a));
            r->EnableAnimation(a);
            if (!r->GetExecutive()->UpdateInformation())  // the time range follows the enabled animations
                throw std::runtime_error(path_ + ": vtkGLTFReader failed with animation " + std::to_string(a) + " enabled");
        }
        it = readers_.emplace(a, r).first;
    }
    return *it->second;
}

VtkPosedMesh VtkGltfPoser::pose(int a, double t) {
    vtkGLTFReader& r = reader(a);
    int errors = 0;
    vtkNew<vtkCallbackCommand> onError;
    onError->SetCallback(countErrors);
    onError->SetClientData(&errors);
    const unsigned long tag = r.AddObserver(vtkCommand::ErrorEvent, onError);
    const int ok = a >= 0 ? r.UpdateTimeStep(t) : (r.Update(), 1);
    r.RemoveObserver(tag);
    const std::string where = path_ + " (animation " + std::to_string(a) + ", t = " + std::to_string(t) + " s)";
    if (!ok || errors > 0) throw std::runtime_error(where + ": vtkGLTFReader reported an error");

    // The output's polydata blocks are overwritten by the next update: copy them now.
    VtkPosedMesh out;
    vtkNew<vtkDataObjectTreeIterator> it;
    it->SetDataSet(r.GetOutput());
    it->VisitOnlyLeavesOn();
    it->TraverseSubTreeOn();
    vtkNew<vtkIdList> cell;
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem()) {
        auto* poly = vtkPolyData::SafeDownCast(it->GetCurrentDataObject());
        if (!poly || !poly->GetPoints()) continue;
        const auto base = static_cast<std::uint32_t>(out.positions.size());
        const vtkIdType n = poly->GetNumberOfPoints();
        for (vtkIdType i = 0; i < n; ++i) {
            double p[3];
            poly->GetPoint(i, p);
            out.positions.emplace_back(p[0], p[1], p[2]);
        }
        out.primitiveVertices.push_back(static_cast<std::size_t>(n));
        vtkCellArray* polys = poly->GetPolys();
        for (polys->InitTraversal(); polys->GetNextCell(cell);) {
            // Triangles as they are; a polygon (VTK may keep one) as a fan.
            for (vtkIdType k = 2; k < cell->GetNumberOfIds(); ++k)
                for (vtkIdType v : {cell->GetId(0), cell->GetId(k - 1), cell->GetId(k)})
                    out.triangles.push_back(base + static_cast<std::uint32_t>(v));
        }
        if (poly->GetNumberOfStrips() > 0) throw std::runtime_error(where + ": triangle strips are not read by this oracle");
    }
    if (out.triangles.empty()) throw std::runtime_error(where + ": VTK read no triangle");
    return out;
}

}  // namespace throng::test
