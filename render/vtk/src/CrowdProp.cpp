#include "throng/vtk/CrowdProp.h"

#include <algorithm>
#include <stdexcept>

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/vtk/CameraCascade.h"

namespace throng::vtk {

vtkStandardNewMacro(CrowdProp)

CrowdProp::CrowdProp() {
    data_ = vtkSmartPointer<vtkPolyData>::New();
    mapper_->SetInputData(data_);
    mapper_->SetScalarModeToUsePointData();
    mapper_->SetColorModeToDirectScalars();
    actor_->SetMapper(mapper_);
}

CrowdProp::~CrowdProp() = default;

void CrowdProp::SetScene(Crowd* crowd, Node* root) {
    cascade_ = std::make_unique<CameraCascade>(crowd, root, "CrowdProp::SetScene");
    Modified();
}

ActorProcessor* CrowdProp::GetProcessor() { return cascade_ ? &cascade_->processor() : nullptr; }

vtkProperty* CrowdProp::GetActorProperty() { return actor_->GetProperty(); }

// Unknown bounds: VTK's cullers keep the prop, whose own cascade culls its actors. Bounds of the
// last frame could be stale, and a crowd culled on them would never be looked at again.
double* CrowdProp::GetBounds() { return nullptr; }

// The draw list's actor meshes as one poly data in world coordinates: rigid parts placed by their
// matrix, skinned ones blended by their palette first (linear-blend skinning on the CPU).
void CrowdProp::buildMeshes() {
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataTypeToFloat();
    auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
    colours->SetName("colour");
    colours->SetNumberOfComponents(3);
    auto polys = vtkSmartPointer<vtkCellArray>::New();
    skipped_ = triangles_ = 0;
    for (const DrawItem& item : cascade_->processor().drawList().items()) {
        if (item.actor == kNoActor) continue;  // the scene's own geometry is the application's to draw
        const auto* mesh = item.representation == Representation::Mesh ? dynamic_cast<const MeshDrawable*>(item.drawable) : nullptr;
        if (!mesh || !item.worldMatrix) {
            ++skipped_;
            continue;
        }
        const MeshData& m = mesh->mesh();
        scratch_.assign(m.positions.begin(), m.positions.end());
        if (item.skinPalette && m.skinned()) {
            for (std::size_t v = 0; v < m.positions.size(); ++v) {
                glm::mat4 blend(0.0f);
                auto add = [&](const glm::u16vec4& j, const glm::vec4& w) {
                    for (int k = 0; k < 4; ++k)
                        if (w[k] != 0.0f && j[k] < item.skinPaletteSize) blend += w[k] * item.skinPalette[j[k]];
                };
                add(m.joints0[v], m.weights0[v]);
                if (!m.joints1.empty()) add(m.joints1[v], m.weights1[v]);
                scratch_[v] = glm::vec3(blend * glm::vec4(m.positions[v], 1.0f));
            }
        }
        const Mat4& world = *item.worldMatrix;
        const auto base = points->GetNumberOfPoints();
        const glm::vec4 c = glm::clamp(m.baseColor * item.tint, 0.0f, 1.0f) * 255.0f;
        const unsigned char rgb[3] = {static_cast<unsigned char>(c.r), static_cast<unsigned char>(c.g), static_cast<unsigned char>(c.b)};
        for (const glm::vec3& p : scratch_) {
            const Vec3 w = Vec3(world * glm::dvec4(glm::dvec3(p), 1.0));
            points->InsertNextPoint(w.x, w.y, w.z);
            colours->InsertNextTypedTuple(rgb);
        }
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            const vtkIdType tri[3] = {base + vtkIdType(m.indices[t]), base + vtkIdType(m.indices[t + 1]), base + vtkIdType(m.indices[t + 2])};
            polys->InsertNextCell(3, tri);
        }
        triangles_ += m.triangleCount();
    }
    data_->SetPoints(points);
    data_->SetPolys(polys);
    data_->GetPointData()->SetScalars(colours);
    data_->Modified();
}

int CrowdProp::RenderOpaqueGeometry(vtkViewport* viewport) {
    auto* renderer = vtkRenderer::SafeDownCast(viewport);
    if (!renderer || !cascade_ || !GetVisibility()) return 0;
    last_ = cascade_->run(*renderer);
    buildMeshes();
    if (data_->GetNumberOfPolys() == 0) return 0;
    return actor_->RenderOpaqueGeometry(viewport);
}

void CrowdProp::ReleaseGraphicsResources(vtkWindow* window) {
    actor_->ReleaseGraphicsResources(window);
    vtkProp3D::ReleaseGraphicsResources(window);
}

}  // namespace throng::vtk
