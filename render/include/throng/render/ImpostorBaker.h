#pragma once
// Bakes an ImpostorAtlas for one actor template and clip (seed 000 §3): renders the figure with
// GlRenderer, orthographically, from every view of a ViewHemisphere at every key-frame, over
// transparent black, and projects every bone (parent joint to child joint) into each cell as a
// feature line. Also renders single cells at any time, the "truth" morphed frames are measured
// against.

#include <functional>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "throng/render/BeierNeely.h"
#include "throng/render/FeatureTrack.h"
#include "throng/render/ImpostorAtlas.h"
#include "throng/render/ProxyMesh.h"
#include "throng/render/ViewHemisphere.h"
#include "throng/scenegraph/Image.h"

namespace throng {

class ActorTemplate;
class GlContext;

/// What to bake.
struct ImpostorBakeOptions {
    int azimuths = 16;       ///< views around
    int elevations = 4;      ///< rings of views from the horizon up
    int keyframes = 16;      ///< key-frames over the clip (it loops)
    int cellSize = 128;      ///< pixels per cell side
    /// ImpostorSet: also give each atlas the figure's surface proxy (ImpostorBaker::proxyMesh), so
    /// its in-betweens are warped through the surface rather than morphed along bone lines.
    bool surfaceProxy = true;
    /// ImpostorSet: how much of each atlas is kept; the rest is regenerated at draw time (today's
    /// default: every other key-frame; Half also drops every other view ring, seed 000 §5).
    AtlasStorage storage = AtlasStorage::HalfKeyframes;
    /// ImpostorSet: vertices of the coarser proxy warped impostors are drawn with (0: the full
    /// proxy; ImpostorBaker::proxyMesh's clustering).
    std::size_t drawProxyVertices = 256;
    /// Called after each key-frame with (done, total), for a progress bar.
    std::function<void(int, int)> progress;
};

/// Renders impostor cells of one template and clip.
class ImpostorBaker {
public:
    /// A baker of `tmpl`'s clip `clip` drawing in `context` (resized to one cell). Samples the clip
    /// to find the volume every view covers. Throws std::invalid_argument if a pointer is null,
    /// the clip does not exist, or an option is out of range.
    ImpostorBaker(std::shared_ptr<GlContext> context, std::shared_ptr<const ActorTemplate> tmpl, int clip,
                  const ImpostorBakeOptions& options = {});
    ~ImpostorBaker();
    ImpostorBaker(const ImpostorBaker&) = delete;
    ImpostorBaker& operator=(const ImpostorBaker&) = delete;

    /// The views baked.
    const ViewHemisphere& views() const;
    /// Renders every view of every key-frame and their feature lines (all key-frames stored).
    ImpostorAtlas bake();
    /// The cell of `view` at clip time `time` (seconds, wrapped), premultiplied RGBA.
    Image renderCell(double time, std::uint32_t view);
    /// The cell seen from unit direction `toEye` (actor frame; any direction with a horizontal
    /// component), as a baked view would be: the truth view blending is measured against.
    /// A figure with body regions is drawn with kBakeLook (every region white).
    Image renderCell(double time, const glm::vec3& toEye);
    /// The body region (BodyRegion) of every texel of `view`'s cell at `time`, top row first, with
    /// two texels around the figure given a neighbour's region (for regenerated cells' rims).
    std::vector<std::uint8_t> renderRegions(double time, std::uint32_t view);
    /// Whether any mesh of `tmpl` has body regions (then bake() records them with the cells).
    static bool hasBodyRegions(const ActorTemplate& tmpl);
    /// The bones of the pose at `time` projected into `view`'s cell (pixels), one per bone.
    std::vector<FeatureLine> projectBones(double time, std::uint32_t view);
    /// The bones in 3-D at every key-frame (the same bones, in the same order, as the atlas's
    /// lines), each bone's flesh radius (median distance of the vertices it carries from it, in the
    /// clip's first pose) and limbs (chains between branchings): the limb-aware features of any view.
    FeatureTrack featureTrack();
    /// The figure's surface as a warping proxy (ProxyWarp): every drawn mesh, skinned, with at
    /// most `maxVertices` vertices (0: all, copies welded; fewer by merging nearby vertices of one
    /// joint), at `samplesPerKeyframe` (>= 1) poses per key-frame interval: proxy key-frame j is
    /// clip time j / samplesPerKeyframe key-frames (finer than the cells, for warping to any time).
    /// Throws std::invalid_argument if samplesPerKeyframe < 1.
    ProxyMesh proxyMesh(std::size_t maxVertices = 0, int samplesPerKeyframe = 1);

private:
    // Renders the figure at `time` seen from `toEye` as the renderer's options say.
    Image render(double time, const glm::vec3& toEye);

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
