#include "throng/vtk/CrowdProp.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkRenderer.h>
#include <vtk_glew.h>
#include <vtkTypeInt32Array.h>
#include <vtkUnsignedCharArray.h>

#include "throng/actors/ActorProcessor.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/vtk/CameraCascade.h"
#include "VtkGlContext.h"

namespace throng::vtk {

vtkStandardNewMacro(CrowdProp)

CrowdProp::CrowdProp() {
    data_ = vtkSmartPointer<vtkPolyData>::New();
    points_->SetNumberOfComponents(3);
    colours_->SetName("colour");
    colours_->SetNumberOfComponents(3);
    mapper_->SetInputData(data_);
    mapper_->SetScalarModeToUsePointData();
    mapper_->SetColorModeToDirectScalars();
    actor_->SetMapper(mapper_);
}

CrowdProp::~CrowdProp() { releaseThrongRenderer(); }

void CrowdProp::SetScene(Crowd* crowd, Node* root) {
    cascade_ = std::make_unique<CameraCascade>(crowd, root, "CrowdProp::SetScene");
    Modified();
}

ActorProcessor* CrowdProp::GetProcessor() { return cascade_ ? &cascade_->processor() : nullptr; }

vtkPolyData* CrowdProp::GetLastMeshes() { return data_; }

vtkProperty* CrowdProp::GetActorProperty() { return actor_->GetProperty(); }

// Unknown bounds: VTK's cullers keep the prop, whose own cascade culls its actors. Bounds of the
// last frame could be stale, and a crowd culled on them would never be looked at again.
double* CrowdProp::GetBounds() { return nullptr; }

// The draw list's actor meshes as one poly data in world coordinates: rigid parts placed by their
// matrix, skinned ones blended by their palette first (linear-blend skinning on the CPU). The arrays
// are kept across renders and written through raw pointers: sized once per frame, no per-point call.
void CrowdProp::buildMeshes() {
    skipped_ = triangles_ = 0;
    parts_.clear();
    std::size_t vertices = 0, indices = 0;
    for (const DrawItem& item : cascade_->processor().drawList().items()) {
        if (item.actor == kNoActor) continue;  // the scene's own geometry is the application's to draw
        const auto* mesh = item.representation == Representation::Mesh ? dynamic_cast<const MeshDrawable*>(item.drawable) : nullptr;
        if (!mesh) {
            ++skipped_;
            continue;
        }
        parts_.push_back({&item, &mesh->mesh()});
        vertices += mesh->mesh().positions.size();
        indices += mesh->mesh().indices.size() / 3 * 3;
        triangles_ += mesh->mesh().triangleCount();
    }
    if (vertices > std::size_t(std::numeric_limits<std::int32_t>::max()))
        throw std::length_error("CrowdProp: " + std::to_string(vertices) + " vertices in one frame exceed 32-bit indices");
    points_->SetNumberOfTuples(vtkIdType(vertices));
    colours_->SetNumberOfTuples(vtkIdType(vertices));
    connectivity_->SetNumberOfTuples(vtkIdType(indices));
    float* xyz = points_->GetPointer(0);
    unsigned char* rgb = colours_->GetPointer(0);
    std::int32_t* tri = connectivity_->GetPointer(0);
    std::int32_t base = 0;
    for (const auto& [item, m] : parts_) {
        scratch_.assign(m->positions.begin(), m->positions.end());
        if (item->skinPalette && m->skinned()) {
            for (std::size_t v = 0; v < m->positions.size(); ++v) {
                glm::mat4 blend(0.0f);
                auto add = [&](const glm::u16vec4& j, const glm::vec4& w) {
                    for (int k = 0; k < 4; ++k)
                        if (w[k] != 0.0f && j[k] < item->skinPaletteSize) blend += w[k] * item->skinPalette[j[k]];
                };
                add(m->joints0[v], m->weights0[v]);
                if (!m->joints1.empty()) add(m->joints1[v], m->weights1[v]);
                scratch_[v] = glm::vec3(blend * glm::vec4(m->positions[v], 1.0f));
            }
        }
        const Mat4 world = item->world.toMat4();
        const glm::vec4 c = glm::clamp(m->baseColor * item->tint, 0.0f, 1.0f) * 255.0f;
        const unsigned char colour[3] = {static_cast<unsigned char>(c.r), static_cast<unsigned char>(c.g), static_cast<unsigned char>(c.b)};
        for (const glm::vec3& p : scratch_) {
            const Vec3 w = Vec3(world * glm::dvec4(glm::dvec3(p), 1.0));
            *xyz++ = float(w.x), *xyz++ = float(w.y), *xyz++ = float(w.z);
            *rgb++ = colour[0], *rgb++ = colour[1], *rgb++ = colour[2];
        }
        for (std::size_t t = 0; t + 2 < m->indices.size(); t += 3)
            for (int k = 0; k < 3; ++k) *tri++ = base + std::int32_t(m->indices[t + std::size_t(k)]);
        base += std::int32_t(m->positions.size());
    }
    points_->Modified();
    colours_->Modified();
    connectivity_->Modified();
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetData(points_);
    auto polys = vtkSmartPointer<vtkCellArray>::New();
    polys->SetData(3, connectivity_);
    data_->SetPoints(points);
    data_->SetPolys(polys);
    data_->GetPointData()->SetScalars(colours_);
    data_->Modified();
}

void CrowdProp::SetThrongDrawing(bool on) {
    if (on == throngDrawing_) return;
    throngDrawing_ = on;
    Modified();
}

const CrowdRenderStatistics* CrowdProp::GetLastRenderStatistics() const { return throngDraw_ ? &throngDraw_->statistics() : nullptr; }

// Throng's renderer draws the draw list into the framebuffer VTK has bound for this renderer, over
// what VTK drew so far (no clear) and against its depth. VTK caches GL state (vtkOpenGLState) and
// which shader it bound last: both are recorded before and put back after, so VTK's next props see
// the state they expect.
int CrowdProp::renderWithThrong(vtkRenderer& renderer) {
    auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer.GetRenderWindow());
    if (!window) {
        vtkErrorMacro("CrowdProp: Throng drawing needs an OpenGL render window");
        return 0;
    }
    if (window_ && window_ != window) releaseThrongRenderer();
    vtkOpenGLState* state = window->GetState();
    state->Reset();
    state->Push();
    int framebuffer = 0;
    state->vtkglGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    int width = 0, height = 0, x = 0, y = 0;
    renderer.GetTiledSizeAndOrigin(&width, &height, &x, &y);
    Stopwatch watch;
    try {
        if (!throngDraw_) {
            glContext_ = std::make_shared<VtkGlContext>();
            CrowdRendererOptions options;
            options.meshes.clear = false;  // VTK's picture and depth stay under the crowd
            options.drawScene = false;     // the application's scene is VTK's to draw
            throngDraw_ = std::make_unique<CrowdRenderer>(glContext_, options);
            window_ = window;
        }
        glContext_->setTarget(unsigned(framebuffer), x, y, width, height);
        throngDraw_->drawFrame(cascade_->camera(), cascade_->processor().drawList());
    } catch (const std::exception& e) {
        state->Pop();
        vtkErrorMacro("CrowdProp: " << e.what());
        return 0;
    }
    state->Pop();
    window->GetShaderCache()->ReleaseCurrentShader();
    buildMs_ = watch.elapsedMs();
    const CrowdRenderStatistics& s = throngDraw_->statistics();
    triangles_ = s.meshes.triangles;
    skipped_ = s.meshes.skippedItems + s.quads.instances;
    return 1;
}

void CrowdProp::releaseThrongRenderer() {
    if (!throngDraw_) return;
    if (window_) window_->MakeCurrent();  // its GL objects live in that window's context
    throngDraw_.reset();
    glContext_.reset();
    window_ = nullptr;
}

int CrowdProp::RenderOpaqueGeometry(vtkViewport* viewport) {
    auto* renderer = vtkRenderer::SafeDownCast(viewport);
    if (!renderer || !cascade_ || !GetVisibility()) return 0;
    last_ = cascade_->run(*renderer);
    if (throngDrawing_) return renderWithThrong(*renderer);
    Stopwatch watch;
    buildMeshes();
    buildMs_ = watch.elapsedMs();
    if (data_->GetNumberOfPolys() == 0) return 0;
    return actor_->RenderOpaqueGeometry(viewport);
}

void CrowdProp::ReleaseGraphicsResources(vtkWindow* window) {
    if (window == window_.GetPointer()) releaseThrongRenderer();
    actor_->ReleaseGraphicsResources(window);
    vtkProp3D::ReleaseGraphicsResources(window);
}

}  // namespace throng::vtk
