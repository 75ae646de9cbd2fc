#pragma once
// One frame of impostors, before any GL: for every ImpostorDrawable item of a draw list, the eye
// direction in the actor's frame picks three views with barycentric weights (ViewHemisphere), the
// actor's clip time picks a key-frame, and dropped key-frames come from the shared MorphCache, so
// each needed cell is morphed once whatever the number of actors. The output is a flat array of
// quad instances a renderer draws in one instanced call. Data-oriented: no allocation per actor
// once warmed up.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>

#include "throng/render/MorphCache.h"
#include "throng/scenegraph/BodyLook.h"
#include "throng/scenegraph/Math.h"

namespace throng {

class Camera;
class DrawList;
class ImpostorDrawable;
struct DrawItem;

/// One camera-facing quad: where, how big, and up to three cells blended.
struct ImpostorInstance {
    Vec3 centre{0.0};                      ///< world centre of the baked volume
    float halfSize = 1.0f;                 ///< half the quad's side (metres)
    glm::vec4 tint{1.0f};                  ///< the actor's tint
    BodyLook look;                         ///< the actor's colours per body region (atlases with regions)
    const ImpostorDrawable* drawable = nullptr;  ///< whose atlas
    std::array<std::uint32_t, 3> views{};  ///< views blended
    std::array<float, 3> weights{};        ///< their weights (sum 1)
    int keyframe = 0;                      ///< key-frame shown
    float phase = 0.0f;                    ///< the clip time in key-frames, in [0, keyframes): warped impostors pose there
    Vec3 origin{0.0};                      ///< the actor's world origin (warped impostors)
    glm::mat3 axes{1.0f};                  ///< the actor transform's 3x3 part, scale included (warped impostors)
    /// Morphed cells of a dropped key-frame, when the batcher has a MorphCache (null for a stored
    /// key-frame, a zero weight, or cells left to the renderer's pool).
    std::array<const Image*, 3> morphed{};
};

/// Per-frame work of the batcher.
struct ImpostorBatchStatistics {
    std::uint64_t impostors = 0;       ///< instances made
    std::uint64_t droppedCells = 0;    ///< cell uses that needed a morphed cell
    double ms = 0;                     ///< time of build(), morphing included
};

/// How an impostor's views are picked for the eye direction (seed 003 §4.1).
struct ImpostorViewChoice {
    bool nearest = false;     ///< the nearest view alone (snapping), else the blend of the three around the eye
    bool smoothstep = false;  ///< the blend's clamped weights through the quintic smoothstep, renormalised (sharper)
    /// Each impostor whose atlas has a surface proxy drawn as that proxy, posed at the actor's clip
    /// time and seen from the real eye, textured from the cells the quad would blend (seed 003
    /// §4.1, the warp in the vertex stage); other atlases as quads.
    bool warped = false;
};

/// Turns impostor draw items into quad instances, morphing through a MorphCache.
class ImpostorBatcher {
public:
    /// A batcher requesting dropped cells from `cache` (which must outlive it) on the CPU side:
    /// every instance showing a dropped key-frame carries its morphed images; views as `views` says.
    explicit ImpostorBatcher(MorphCache& cache, ImpostorViewChoice views = {});
    /// A batcher that morphs nothing: instances of dropped key-frames carry no image, and the
    /// renderer's pool of morphed cells provides them (ImpostorRenderer).
    explicit ImpostorBatcher(ImpostorViewChoice views = {});
    /// Starts the cache's frame and builds the instances of `list`'s impostor items (an
    /// ImpostorDrawable, Representation::Impostor) seen by `camera`; each shows the key-frame of
    /// the clip time its item records. Other items are ignored.
    void build(const DrawList& list, const Camera& camera);
    /// The instances of the last build().
    const std::vector<ImpostorInstance>& instances() const { return instances_; }
    /// Statistics of the last build().
    const ImpostorBatchStatistics& statistics() const { return stats_; }

private:
    MorphCache* cache_;
    ImpostorViewChoice views_;
    std::vector<ImpostorInstance> instances_;
    ImpostorBatchStatistics stats_;
};

}  // namespace throng
