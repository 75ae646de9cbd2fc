#pragma once
// The morph cache (DESIGN.md, Impostors): every dropped key-frame cell a frame needs, per
// (atlas, i.e. template and clip; view; key-frame), is synthesised at most once per frame and
// shared by all actors showing it, so morphing work grows with views x frames in use, not with
// the crowd. Cells may be retained across frames up to a capacity (least recently used first out).

#include <cstdint>
#include <list>
#include <memory>
#include <unordered_map>
#include <vector>

#include "throng/render/BeierNeely.h"
#include "throng/render/ImpostorAtlas.h"
#include "throng/scenegraph/Image.h"

namespace throng {

class GpuMorpher;

/// How the cache morphs.
struct MorphCacheOptions {
    MorphParameters parameters;          ///< Beier-Neely a, b, p
    std::size_t features = 1000;         ///< feature lines per cell: the strongest bones of the atlas
    /// Target lines of the in-between: the baked skeleton's own projection (true) or the
    /// interpolation of the neighbours' lines (false, the paper's choice).
    bool skeletonTargets = true;
    std::size_t capacity = 0;            ///< cells kept across frames (0: only within a frame)
    unsigned threads = 1;                ///< CPU morphing threads per cell
};

/// Work of the current frame.
struct MorphCacheStatistics {
    std::uint64_t requests = 0;     ///< cells asked for
    std::uint64_t synthesized = 0;  ///< cells morphed
    std::uint64_t hits = 0;         ///< requests served by a cell already made
    std::size_t resident = 0;       ///< cells held
    double morphMs = 0;             ///< time spent morphing the synthesized cells
};

/// What morphing one dropped cell takes: the two stored cells it lies between, the fraction
/// between them, and the three line sets (the strongest `options.features` bones). A dropped
/// key-frame lies between its stored key-frames in the same view; a view on a dropped ring of a
/// stored key-frame between the views of the rings below and above (same azimuth); a cell whose
/// key-frame and ring are both dropped between the key-frames around it, in the view of the
/// nearer stored ring (lines morph two images only: the surface proxy blends all four).
struct DroppedCellLines {
    /// Stored key-frame of the first cell (wrapping: clips loop).
    int before = 0, after = 0;                  ///< stored key-frame of the second cell
    /// \var fromView
    /// View of the first cell.
    std::uint32_t fromView = 0, toView = 0;     ///< view of the second cell
    float t = 0.5f;                             ///< fraction from the first cell to the second
    /// \var from
    /// Lines in `before`, one per bone.
    /// \var to
    /// Lines in `after`, one per bone.
    std::vector<FeatureLine> from, to, target;  ///< lines of the in-between, one per bone
};

/// The neighbours and lines of dropped cell (`view`, `keyframe`) of `atlas`. Throws
/// std::invalid_argument if the cell is out of range or stored.
DroppedCellLines droppedCellLines(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe, const MorphCacheOptions& options);

/// The dropped cell (`view`, `keyframe`) of `atlas`: its stored neighbours (droppedCellLines)
/// morphed with the strongest `options.features` bones. With `gpu`, morphed there.
Image morphDroppedCell(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe, const MorphCacheOptions& options,
                       GpuMorpher* gpu = nullptr);

/// Dropped cells synthesised on demand and shared within (and, up to a capacity, across) frames.
class MorphCache {
public:
    /// A cache morphing with `options`, on `gpu` when it is given (it must outlive the cache).
    explicit MorphCache(const MorphCacheOptions& options = {}, GpuMorpher* gpu = nullptr);
    ~MorphCache();

    /// Starts a frame: resets the statistics; without capacity, forgets every cell; else evicts
    /// the least recently used cells beyond the capacity.
    void beginFrame();
    /// The dropped cell (`view`, `keyframe`) of `atlas`, morphed now if this frame (or a retained
    /// one) has not made it. The reference stays valid until beginFrame(). Throws
    /// std::invalid_argument if the cell is stored or out of range.
    const Image& request(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe);
    /// Statistics of the current frame.
    const MorphCacheStatistics& statistics() const { return stats_; }
    /// Options.
    const MorphCacheOptions& options() const { return options_; }

private:
    struct Key {
        const ImpostorAtlas* atlas;
        std::uint32_t view;
        int keyframe;
        bool operator==(const Key&) const = default;
    };
    struct KeyHash {
        std::size_t operator()(const Key& k) const {
            return std::hash<const void*>()(k.atlas) ^ (static_cast<std::size_t>(k.view) * 0x9E3779B97F4A7C15ull) ^
                   (static_cast<std::size_t>(k.keyframe) << 20);
        }
    };
    struct Entry {
        Image image;
        std::list<Key>::iterator lru;
    };
    MorphCacheOptions options_;
    GpuMorpher* gpu_;
    std::unordered_map<Key, Entry, KeyHash> cells_;
    std::list<Key> lru_;  // most recently used first
    MorphCacheStatistics stats_;
};

}  // namespace throng
