#pragma once
// A crowd inside an ordinary vtkRenderer: a VTK prop that, each time the renderer draws it, runs
// Throng's actor cascade (culling, LOD, behavioural LOD, poses) for the renderer's active camera
// and draws the visible actors in VTK's own OpenGL context, so they share the depth buffer with the
// scene's other props (a cone in front hides the actors behind it). Two ways, measured side by side
// by bench_vtk_crowd_prop:
//  - Throng's renderer (SetThrongDrawing(true)): CrowdRenderer draws the draw list into the frame
//    VTK is rendering (GPU skinning, instancing, textures, key-pose cache items), VTK's GL state
//    saved before and restored after;
//  - a VTK mapper (the default): the meshes placed and skinned on the CPU into one poly data,
//    coloured by their material's base colour times the actor's tint; textures, impostors and
//    key-pose cache items are not drawn (GetLastSkippedItems counts them).
//
//   auto crowdProp = vtkSmartPointer<throng::vtk::CrowdProp>::New();
//   crowdProp->SetScene(&crowd, root.get());   // the application steps the crowd
//   renderer->AddViewProp(crowdProp);

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <vtkNew.h>
#include <vtkProp3D.h>
#include <vtkSmartPointer.h>
#include <vtkWeakPointer.h>

#include "throng/actors/ActorFrameStatistics.h"

class vtkActor;
class vtkFloatArray;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkProperty;
class vtkRenderer;
class vtkRenderWindow;
class vtkTypeInt32Array;
class vtkUnsignedCharArray;
class vtkViewport;
class vtkWindow;

namespace throng {
class ActorProcessor;
class Crowd;
class CrowdRenderer;
struct CrowdRenderStatistics;
class Node;
struct DrawItem;
struct MeshData;
}  // namespace throng

namespace throng::vtk {

class CameraCascade;
class VtkGlContext;

/// Draws a Throng crowd in a VTK scene, culled and posed by the actor cascade for VTK's camera.
class CrowdProp : public vtkProp3D {
public:
    /// A new prop (VTK reference counting).
    static CrowdProp* New();
    /// \cond
    // Hidden from Doxygen: with no semicolon after it, the macro and SetScene read as one.
    vtkTypeMacro(CrowdProp, vtkProp3D)
    /// \endcond

    /// Draws the actors of `crowd` held by nodes under `root` (both must outlive the prop; the
    /// application steps the crowd; generic nodes under `root` are not drawn by the prop). Makes a
    /// fresh ActorProcessor. Throws std::invalid_argument if either is null.
    void SetScene(Crowd* crowd, Node* root);
    /// The processor running the cascade (LOD scale, threads, occlusion are the application's to
    /// set); null before SetScene. Its statistics and draw list are those of the last render.
    ActorProcessor* GetProcessor();
    /// Statistics of the cascade in the last render.
    const ActorFrameStatistics& GetLastStatistics() const { return last_; }
    /// Draw items of actors the last render did not draw (impostors, key-pose cache items).
    std::uint64_t GetLastSkippedItems() const { return skipped_; }
    /// Triangles the last render drew.
    std::uint64_t GetLastTriangles() const { return triangles_; }
    /// Mapper drawing: milliseconds the last render spent skinning the actors and filling the poly
    /// data (after the cascade, before VTK's mapper). Throng drawing: the renderer's whole draw.
    double GetLastBuildMs() const { return buildMs_; }
    /// Mapper drawing: the actors' meshes drawn in the last render, in world coordinates (point data
    /// "colour"); empty under Throng drawing.
    vtkPolyData* GetLastMeshes();
    /// The look of the actors' meshes (lighting, shading); colours come from the meshes. Mapper
    /// drawing only.
    vtkProperty* GetActorProperty();
    /// Draws with Throng's own renderer in VTK's context (true) or through a VTK mapper (false, the
    /// default). Throng drawing needs an OpenGL render window on X (GLX), as Debian's VTK has.
    void SetThrongDrawing(bool on);
    /// Whether Throng's renderer draws the actors.
    bool GetThrongDrawing() const { return throngDrawing_; }
    /// Throng drawing: the statistics of the renderer's last frame (null before the first).
    const CrowdRenderStatistics* GetLastRenderStatistics() const;

    /// Null (unknown): VTK's cullers then keep the prop, and its own cascade culls the actors. The
    /// crowd's bounds of the last frame could be stale, and a crowd culled on them would never be
    /// processed again. (So vtkRenderer::ResetCamera does not frame the crowd.)
    double* GetBounds() override;
    using vtkProp3D::GetBounds;
    /// Runs the cascade for the viewport's active camera and draws the visible actors.
    int RenderOpaqueGeometry(vtkViewport* viewport) override;
    /// The crowd's meshes are opaque.
    vtkTypeBool HasTranslucentPolygonalGeometry() override { return 0; }
    /// Frees the mapper's and Throng's renderer's GPU resources for `window`.
    void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
    CrowdProp();
    ~CrowdProp() override;

private:
    CrowdProp(const CrowdProp&) = delete;
    void operator=(const CrowdProp&) = delete;
    void buildMeshes();
    int renderWithThrong(vtkRenderer& renderer);
    void releaseThrongRenderer();

    std::unique_ptr<CameraCascade> cascade_;
    ActorFrameStatistics last_;
    std::uint64_t skipped_ = 0, triangles_ = 0;
    double buildMs_ = 0;
    bool throngDrawing_ = false;
    std::shared_ptr<VtkGlContext> glContext_;   // VTK's context, as Throng's renderer sees it
    std::unique_ptr<CrowdRenderer> throngDraw_; // made in the first render of Throng drawing
    vtkWeakPointer<vtkRenderWindow> window_;    // whose context holds throngDraw_'s GL objects
    vtkNew<vtkActor> actor_;
    vtkNew<vtkPolyDataMapper> mapper_;
    vtkSmartPointer<vtkPolyData> data_;
    vtkNew<vtkFloatArray> points_;          // the frame's vertices, world coordinates
    vtkNew<vtkUnsignedCharArray> colours_;  // their colours
    vtkNew<vtkTypeInt32Array> connectivity_;// three indices per triangle
    std::vector<std::pair<const DrawItem*, const MeshData*>> parts_;  // the frame's meshes drawn
    std::vector<glm::vec3> scratch_;  // one mesh's skinned positions
};

}  // namespace throng::vtk
