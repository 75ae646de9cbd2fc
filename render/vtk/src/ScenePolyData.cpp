#include "throng/vtk/ScenePolyData.h"

#include <vector>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/NodeVisitor.h"
#include "throng/scenegraph/Transform.h"

namespace throng::vtk {
namespace {

// Walks the scene top-down composing local matrices (the scene need not have been processed: no
// world matrix of a previous frame is trusted) and appends each mesh leaf's triangles.
class TriangleGatherer : public NodeVisitor {
public:
    using NodeVisitor::apply;

    void apply(Transform& transform) override {
        const Mat4 saved = world_;
        world_ = world_ * transform.localMatrix();
        traverse(transform);
        world_ = saved;
    }
    void apply(LOD& lod) override {
        if (lod.childCount() > 0) lod.child(0).accept(*this);  // children ordered from the highest detail
    }
    void apply(Geometry& geometry) override {
        const auto* mesh = dynamic_cast<const MeshDrawable*>(&geometry.drawable());
        if (!mesh) {
            ++stats.skipped;
            return;
        }
        const MeshData& m = mesh->mesh();
        const std::size_t base = points.size() / 3;
        for (const glm::vec3& p : m.positions) {
            const Vec3 w = Vec3(world_ * glm::dvec4(glm::dvec3(p), 1.0));
            points.insert(points.end(), {w.x, w.y, w.z});
        }
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3)
            for (int k = 0; k < 3; ++k) triangles.push_back(static_cast<vtkIdType>(base + m.indices[i + std::size_t(k)]));
        meshOf.insert(meshOf.end(), m.triangleCount(), static_cast<int>(stats.meshes));
        ++stats.meshes;
        stats.triangles += m.triangleCount();
    }

    std::vector<double> points;        // x y z per vertex
    std::vector<vtkIdType> triangles;  // three point indices per triangle
    std::vector<int> meshOf;           // per triangle: the leaf it came from
    ScenePolyDataStatistics stats;

private:
    Mat4 world_{1.0};
};

}  // namespace

vtkSmartPointer<vtkPolyData> scenePolyData(Node& root, ScenePolyDataStatistics* stats) {
    TriangleGatherer gather;
    root.accept(gather);

    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(static_cast<vtkIdType>(gather.points.size() / 3));
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) points->SetPoint(i, &gather.points[std::size_t(i) * 3]);

    const auto triangleCount = static_cast<vtkIdType>(gather.triangles.size() / 3);
    auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
    offsets->SetNumberOfValues(triangleCount + 1);
    for (vtkIdType i = 0; i <= triangleCount; ++i) offsets->SetValue(i, 3 * i);
    auto connectivity = vtkSmartPointer<vtkIdTypeArray>::New();
    connectivity->SetNumberOfValues(static_cast<vtkIdType>(gather.triangles.size()));
    for (std::size_t i = 0; i < gather.triangles.size(); ++i) connectivity->SetValue(static_cast<vtkIdType>(i), gather.triangles[i]);
    auto polys = vtkSmartPointer<vtkCellArray>::New();
    polys->SetData(offsets, connectivity);

    auto mesh = vtkSmartPointer<vtkIntArray>::New();
    mesh->SetName("mesh");
    mesh->SetNumberOfValues(triangleCount);
    for (vtkIdType i = 0; i < triangleCount; ++i) mesh->SetValue(i, gather.meshOf[std::size_t(i)]);

    auto data = vtkSmartPointer<vtkPolyData>::New();
    data->SetPoints(points);
    data->SetPolys(polys);
    data->GetCellData()->AddArray(mesh);
    if (stats) *stats = gather.stats;
    return data;
}

}  // namespace throng::vtk
