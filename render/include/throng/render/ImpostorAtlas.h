#pragma once
// A baked impostor of one template playing one clip (seed 000 §3): a cell image per view (on a
// ViewHemisphere) and key-frame, and the skeleton's bones projected into every cell as feature
// lines. Key-frames are stored as pages (one atlas image per key-frame: views in a grid, one row
// per stored view ring); a dropped key-frame keeps its feature lines (a few floats) but not its
// page, and a dropped ring keeps its lines but no row in any page: their cells are regenerated
// from the stored cells around them (seed 000 §5: intermediate key-frames and viewpoints).
// Saved as one PNG per stored key-frame plus impostor.json.

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "throng/render/BeierNeely.h"
#include "throng/render/ProxyMesh.h"
#include "throng/render/ViewHemisphere.h"
#include "throng/scenegraph/Image.h"

namespace throng {

/// A stored cell that a dropped one is regenerated from, with its share.
struct CellSource {
    std::uint32_t view = 0;  ///< stored view
    int keyframe = 0;        ///< stored key-frame
    float weight = 1.0f;     ///< share in the regenerated cell (the sources' shares sum to 1)
};

/// The stored cells around a dropped one: the stored key-frames before and after it times the
/// stored rings below and above it (same azimuth), at most four, weights bilinear in the gaps.
struct CellSources {
    std::array<CellSource, 4> cells{};  ///< the first `count` are used
    int count = 0;                      ///< how many
};

/// How much of an atlas is stored (the rest is regenerated at draw time).
enum class AtlasStorage : std::uint8_t {
    Full,           ///< every key-frame of every view
    HalfKeyframes,  ///< every other key-frame (dropOddKeyframes)
    Half,           ///< every other key-frame and every other view ring (seed 000 §5)
};

/// Views x key-frames of one template and clip, with per-cell feature lines.
class ImpostorAtlas {
public:
    /// An empty atlas of `keyframes` (>= 2) key-frames of a looping clip lasting `duration` seconds
    /// (key-frame k at k * duration / keyframes), cells of `cellSize` (>= 8) pixels, views on
    /// `views`, bones named `boneNames`. Pages start stored and transparent. Throws
    /// std::invalid_argument for out-of-range values.
    ImpostorAtlas(std::string templateName, std::string clipName, const ViewHemisphere& views, int keyframes,
                  double duration, int cellSize, std::vector<std::string> boneNames);

    /// Template name.
    const std::string& templateName() const { return templateName_; }
    /// Clip name.
    const std::string& clipName() const { return clipName_; }
    /// The baked viewpoints.
    const ViewHemisphere& views() const { return views_; }
    /// Number of key-frames, stored or dropped.
    int keyframeCount() const { return keyframes_; }
    /// Clip duration (seconds).
    double duration() const { return duration_; }
    /// Cell size in pixels (cells are square).
    int cellSize() const { return cellSize_; }
    /// Names of the bones giving feature lines (the child node of each bone).
    const std::vector<std::string>& boneNames() const { return boneNames_; }
    /// Number of bones (feature lines per cell).
    std::size_t boneCount() const { return boneNames_.size(); }

    /// Half-size (metres) of the square every view covers, and its centre in the actor frame.
    float worldRadius() const { return radius_; }
    /// Centre of the baked volume in the actor frame (the quad is drawn there).
    const glm::vec3& worldCentre() const { return centre_; }
    /// Sets the covered volume (for drawing quads of the right size).
    void setWorldBounds(const glm::vec3& centre, float radius) { centre_ = centre, radius_ = radius; }

    /// Importance of each bone for choosing a subset of features (the bake uses bone length).
    const std::vector<float>& boneImportance() const { return importance_; }
    /// Sets the importance of every bone (boneCount() values).
    void setBoneImportance(std::vector<float> importance);
    /// The `count` most important bones (all when count >= boneCount()), in bone order.
    std::vector<std::uint32_t> strongestBones(std::size_t count) const;

    /// Whether key-frame `k`'s page is kept.
    bool stored(int keyframe) const { return !pages_[static_cast<std::size_t>(keyframe)].rgba.empty(); }
    /// Whether view ring `ring` has a row in the pages.
    bool ringStored(int ring) const { return ringRow_[static_cast<std::size_t>(ring)] >= 0; }
    /// Whether the cell of `view` in key-frame `k` is stored (its key-frame and its ring are).
    bool cellStored(std::uint32_t view, int keyframe) const {
        return stored(keyframe) && ringStored(static_cast<int>(view / static_cast<std::uint32_t>(views_.azimuths())));
    }
    /// The page of key-frame `k` (empty when dropped).
    const Image& page(int keyframe) const { return pages_[static_cast<std::size_t>(keyframe)]; }
    /// Copies `cell` (cellSize()^2, premultiplied RGBA) into view `view` of key-frame `k`'s page.
    /// Throws std::invalid_argument if the cell was dropped or the size is wrong.
    void setCell(std::uint32_t view, int keyframe, const Image& cell);
    /// A copy of the cell of `view` in key-frame `k`. Throws std::invalid_argument if the cell
    /// was dropped.
    Image cell(std::uint32_t view, int keyframe) const;
    /// Feature lines (one per bone, cell pixels) of `view` in key-frame `k`, stored or dropped.
    std::span<const FeatureLine> lines(std::uint32_t view, int keyframe) const;
    /// Writable feature lines of `view` in key-frame `k`.
    std::span<FeatureLine> lines(std::uint32_t view, int keyframe);

    /// Drops the pages of every odd key-frame (the seed's halving); an odd keyframeCount() keeps
    /// the last one so every dropped frame has stored neighbours.
    void dropOddKeyframes();
    /// Drops every odd view ring (1, 3, ...) from every page; ring 0, the horizon, stays, so
    /// each dropped ring has a stored ring below it (the top one, with an even ring count, only
    /// that: it is regenerated from below). Throws std::invalid_argument with a single ring.
    void dropOddRings();
    /// Drops what `storage` says (nothing, odd key-frames, or odd key-frames and odd rings).
    void drop(AtlasStorage storage);
    /// Stored neighbours of a dropped key-frame (wrapping: clips loop) and the fraction between
    /// them. Throws std::invalid_argument if `k` is stored or has no stored neighbour.
    void neighbours(int keyframe, int& before, int& after, float& t) const;
    /// Stored rings around a dropped ring and the fraction between them (by elevation); a ring
    /// with none stored above gives above == below and t 0. Throws std::invalid_argument if
    /// `ring` is stored or out of range.
    void ringNeighbours(int ring, int& below, int& above, float& t) const;
    /// The stored cells that cell (`view`, `keyframe`) is regenerated from (the cell itself, with
    /// weight 1, when it is stored). Throws std::invalid_argument for a cell out of range.
    CellSources sources(std::uint32_t view, int keyframe) const;
    /// Bytes of texture the stored pages take (RGBA8, no mipmaps).
    std::size_t textureBytes() const;
    /// Bytes the pages would take with every key-frame stored.
    std::size_t fullTextureBytes() const;

    /// Whether the atlas holds body regions (then its cells were baked with kBakeLook, every
    /// region white, for the draw to multiply by each actor's BodyLook).
    bool hasRegions() const { return !regions_.empty(); }
    /// The body region (BodyRegion) of every texel of cell (`view`, `keyframe`), cellSize()^2
    /// bytes, top row first; kept for every cell, stored or dropped (a byte per texel: a quarter of
    /// a colour cell), so regenerated cells need no regions of their own. Empty without regions.
    std::span<const std::uint8_t> regions(std::uint32_t view, int keyframe) const;
    /// Sets the regions of cell (`view`, `keyframe`); the first call gives every other cell
    /// region 0 (none). Throws std::invalid_argument if the cell is out of range, the size is not
    /// cellSize()^2 or a value is not a BodyRegion.
    void setRegions(std::uint32_t view, int keyframe, std::span<const std::uint8_t> regions);
    /// Bytes of texture the region maps take (one per texel of every cell; 0 without regions).
    std::size_t regionBytes() const { return regions_.size(); }

    /// The figure's surface for warping cells (ProxyWarp), or null when the atlas has none (then
    /// in-betweens are morphed with the feature lines). Not saved: a loaded atlas has none.
    const std::shared_ptr<const ProxyMesh>& proxy() const { return proxy_; }
    /// Sets (or clears, with null) the surface proxy. Throws std::invalid_argument if its
    /// key-frames or cell size differ from the atlas's.
    void setProxy(std::shared_ptr<const ProxyMesh> proxy);
    /// The coarser surface warped impostors are drawn with (fewer vertices: drawn once per
    /// impostor and frame), or proxy() when none was set.
    const std::shared_ptr<const ProxyMesh>& drawProxy() const { return drawProxy_ ? drawProxy_ : proxy_; }
    /// Sets (or clears) the drawing proxy. Throws as setProxy().
    void setDrawProxy(std::shared_ptr<const ProxyMesh> proxy);

    /// Writes impostor.json and `keyframe-<k>.png` for each stored key-frame (and with regions
    /// `regions-<k>.png`, the region times 60 in red, for every key-frame) into `directory`
    /// (created). Throws std::runtime_error naming the file on failure.
    void save(const std::filesystem::path& directory) const;
    /// Reads what save() wrote. Throws std::runtime_error naming the file and the problem.
    static ImpostorAtlas load(const std::filesystem::path& directory);
    /// Overrides feature lines with a hand-written feature file (JSON): {"bones": [names]} keeps
    /// only those bones; {"cells": [{"view": v, "keyframe": k, "lines": [[x0, y0, x1, y1], ...]}]}
    /// replaces the lines of those cells (as many lines as bones). Throws std::runtime_error naming
    /// the file and the problem.
    void applyFeatureFile(const std::filesystem::path& file);

private:
    // Top-left pixel of a stored cell in its page; throws naming `who` when the cell is not stored.
    std::pair<int, int> cellOrigin(const char* who, std::uint32_t view, int keyframe) const;
    // Throws std::invalid_argument naming `who` if `proxy` is for other key-frames or cells.
    void checkProxy(const ProxyMesh* proxy, const char* who) const;

    std::string templateName_, clipName_;
    ViewHemisphere views_;
    int keyframes_;
    double duration_;
    int cellSize_;
    std::vector<std::string> boneNames_;
    std::vector<float> importance_;
    glm::vec3 centre_{0.0f};
    float radius_ = 1.0f;
    std::vector<Image> pages_;               // per key-frame; empty rgba when dropped
    std::vector<int> ringRow_;               // per ring: its row in the pages, -1 when dropped
    std::vector<FeatureLine> lines_;         // [keyframe][view][bone]
    std::vector<std::uint8_t> regions_;      // [keyframe][view][texel], or empty
    std::shared_ptr<const ProxyMesh> proxy_, drawProxy_;
};

}  // namespace throng
