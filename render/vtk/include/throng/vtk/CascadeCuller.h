#pragma once
// A vtkCuller that culls VTK props standing for Throng actors with Throng's actor cascade (seed
// 002 §4.2-4.3) for the renderer's active camera: each Cull() processes the crowd's scene with an
// ActorProcessor, so actors are rejected with their generic group, by their Refpoint Bsphere
// (CULL 1) or by their Sklsroot Bsphere (CULL 2), from the crowd's own state, without asking a prop
// for its bounds. The props of rejected actors leave the renderer's list; props that stand for no
// actor are left as they are, for the renderer's other cullers. Install it in place of (or before)
// VTK's default vtkFrustumCoverageCuller:
//
//   auto culler = vtkSmartPointer<throng::vtk::CascadeCuller>::New();
//   culler->SetScene(&crowd, root.get());
//   for (ActorId id ...) culler->SetActorProp(id, prop[id]);
//   renderer->GetCullers()->RemoveAllItems();
//   renderer->AddCuller(culler);

#include <memory>
#include <unordered_map>
#include <vector>

#include <vtkCuller.h>

#include "throng/actors/ActorFrameStatistics.h"
#include "throng/actors/ActorId.h"

class vtkProp;
class vtkRenderer;

namespace throng {
class ActorProcessor;
class Crowd;
class Node;
}  // namespace throng

namespace throng::vtk {

class CameraCascade;

/// Culls actor props with the actor cascade.
class CascadeCuller : public vtkCuller {
public:
    /// A new culler (VTK reference counting).
    static CascadeCuller* New();
    /// \cond
    // Hidden from Doxygen: with no semicolon after it, the macro and SetScene read as one.
    vtkTypeMacro(CascadeCuller, vtkCuller)
    /// \endcond

    /// Culls the actors of `crowd` held by nodes under `root` (both must outlive the culler; the
    /// application steps the crowd). Makes a fresh ActorProcessor; props set before are kept.
    /// Throws std::invalid_argument if either is null.
    void SetScene(Crowd* crowd, Node* root);
    /// Prop `prop` stands for actor `id` (null removes the actor's prop; a prop given for another
    /// actor stands for that one only). The culler does not own
    /// props: the renderer does. Throws std::invalid_argument if no scene is set or `id` is not
    /// an actor of its crowd.
    void SetActorProp(ActorId id, vtkProp* prop);
    /// The processor running the cascade (its LOD scale, threads, occlusion are the application's
    /// to set); null before SetScene. Its statistics and draw list are those of the last Cull().
    ActorProcessor* GetProcessor();
    /// Statistics of the cascade in the last Cull().
    const ActorFrameStatistics& GetLastStatistics() const { return last_; }
    /// Props kept and removed by the last Cull() among those standing for actors.
    int GetLastKept() const { return kept_; }
    /// See GetLastKept().
    int GetLastRemoved() const { return removed_; }

    /// Runs the cascade for `renderer`'s active camera at the crowd's time, removes the props of
    /// rejected actors from `props` (shortening `count`, keeping the others in order) and sets the
    /// kept actor props' render time multiplier (1 on the first culler, else left as the earlier
    /// culler set it). Returns the sum of the kept props' multipliers. Without a scene it does
    /// nothing.
    double Cull(vtkRenderer* renderer, vtkProp** props, int& count, int& initialized) override;

protected:
    CascadeCuller();
    ~CascadeCuller() override;

private:
    CascadeCuller(const CascadeCuller&) = delete;
    void operator=(const CascadeCuller&) = delete;

    std::unique_ptr<CameraCascade> cascade_;
    std::unordered_map<const vtkProp*, ActorId> actorOf_;  // the actor each prop stands for
    std::vector<const vtkProp*> propOf_;                    // per actor: its prop, or null
    ActorFrameStatistics last_;
    int kept_ = 0, removed_ = 0;
};

}  // namespace throng::vtk
