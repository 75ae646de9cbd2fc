#pragma once
// The town's far actors as impostors: bakes every template in use from its main clip (half the
// key-frames kept, the others morphed at run time), hands them to the ActorProcessor, and draws
// the impostor items of each frame as camera-facing quads after the meshes.

#include <functional>
#include <memory>
#include <vector>

#include "throng/actors/ActorProcessor.h"
#include "throng/render/GpuMorpher.h"
#include "throng/render/ImpostorBatcher.h"
#include "throng/render/ImpostorDrawable.h"
#include "throng/render/ImpostorRenderer.h"
#include "throng/render/MorphCache.h"
#include "throng/sim/Simulation.h"

namespace throng::town {

/// Impostors of one town: baked once, drawn every frame.
class TownImpostors {
public:
    /// Bakes the impostors of every template `world` uses, `cellSize` pixels per cell, reporting
    /// (done, total) key-frames to `progress`.
    TownImpostors(std::shared_ptr<GlContext> context, const sim::Simulation& world, int cellSize,
                  const std::function<void(int, int)>& progress);
    /// Makes `processor` draw actors beyond `distance` (with `hysteresis`, metres) as impostors.
    void attach(ActorProcessor& processor, double distance, double hysteresis) const;
    /// Draws the impostor items of `list` (after the meshes of the same frame).
    void draw(const DrawList& list, const Camera& camera, double time);
    /// Cells morphed in the last frame.
    std::uint64_t cellsMorphed() const { return cache_.statistics().synthesized; }
    /// Milliseconds spent making the last frame's quads, morphing included.
    double batchMs() const { return batcher_.statistics().ms; }
    /// Texture memory of the baked atlases (bytes).
    std::size_t textureBytes() const;

private:
    struct Baked {
        const ActorTemplate* tmpl;
        std::shared_ptr<const ImpostorDrawable> drawable;
        std::shared_ptr<const ImpostorAtlas> atlas;
    };
    std::vector<Baked> baked_;
    GpuMorpher gpu_;
    MorphCache cache_;
    ImpostorBatcher batcher_;
    ImpostorRenderer quads_;
};

}  // namespace throng::town
