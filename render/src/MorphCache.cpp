#include "throng/render/MorphCache.h"

#include <stdexcept>
#include <string>

#include "throng/render/GpuMorpher.h"
#include "throng/scenegraph/Stopwatch.h"

namespace throng {

DroppedCellLines droppedCellLines(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe, const MorphCacheOptions& options) {
    if (keyframe < 0 || keyframe >= atlas.keyframeCount() || view >= atlas.views().viewCount())
        throw std::invalid_argument("droppedCellLines: view " + std::to_string(view) + " key-frame " +
                                    std::to_string(keyframe) + " out of range");
    if (atlas.cellStored(view, keyframe))
        throw std::invalid_argument("droppedCellLines: view " + std::to_string(view) + " key-frame " + std::to_string(keyframe) +
                                    " is stored");
    DroppedCellLines c;
    const auto azimuths = static_cast<std::uint32_t>(atlas.views().azimuths());
    const int ring = static_cast<int>(view / azimuths);
    std::uint32_t targetView = view;
    c.fromView = c.toView = view;
    if (!atlas.ringStored(ring)) {
        int below = ring, above = ring;
        float tr = 0.0f;
        atlas.ringNeighbours(ring, below, above, tr);
        const std::uint32_t vb = static_cast<std::uint32_t>(below) * azimuths + view % azimuths;
        const std::uint32_t va = static_cast<std::uint32_t>(above) * azimuths + view % azimuths;
        if (atlas.stored(keyframe)) {  // a view morph within the key-frame
            c.before = c.after = keyframe;
            c.fromView = vb, c.toView = va, c.t = tr;
        } else {  // the nearer stored ring's view stands in for the dropped one
            c.fromView = c.toView = targetView = tr <= 0.5f ? vb : va;
        }
    }
    if (!atlas.stored(keyframe)) atlas.neighbours(keyframe, c.before, c.after, c.t);
    const std::vector<std::uint32_t> bones = atlas.strongestBones(options.features);
    for (std::uint32_t b : bones) {
        c.from.push_back(atlas.lines(c.fromView, c.before)[b]);
        c.to.push_back(atlas.lines(c.toView, c.after)[b]);
        c.target.push_back(atlas.lines(targetView, keyframe)[b]);
    }
    if (!options.skeletonTargets) interpolateLines(c.from, c.to, c.t, c.target);
    return c;
}

Image morphDroppedCell(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe, const MorphCacheOptions& options,
                       GpuMorpher* gpu) {
    const DroppedCellLines c = droppedCellLines(atlas, view, keyframe, options);
    const Image a = atlas.cell(c.fromView, c.before), b = atlas.cell(c.toView, c.after);
    return gpu ? gpu->morph(a, c.from, b, c.to, c.target, c.t, options.parameters)
               : morphImages(a, c.from, b, c.to, c.target, c.t, options.parameters, options.threads);
}

MorphCache::MorphCache(const MorphCacheOptions& options, GpuMorpher* gpu) : options_(options), gpu_(gpu) {}

MorphCache::~MorphCache() = default;

void MorphCache::beginFrame() {
    stats_ = {};
    while (cells_.size() > options_.capacity) {
        cells_.erase(lru_.back());
        lru_.pop_back();
    }
    stats_.resident = cells_.size();
}

const Image& MorphCache::request(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe) {
    ++stats_.requests;
    const Key key{&atlas, view, keyframe};
    if (auto it = cells_.find(key); it != cells_.end()) {
        ++stats_.hits;
        lru_.splice(lru_.begin(), lru_, it->second.lru);
        return it->second.image;
    }
    if (keyframe < 0 || keyframe >= atlas.keyframeCount() || view >= atlas.views().viewCount() || atlas.cellStored(view, keyframe))
        throw std::invalid_argument("MorphCache::request: view " + std::to_string(view) + " key-frame " + std::to_string(keyframe) +
                                    " is not a dropped cell");
    Stopwatch watch;
    Image image = morphDroppedCell(atlas, view, keyframe, options_, gpu_);
    stats_.morphMs += watch.elapsedMs();
    ++stats_.synthesized;
    lru_.push_front(key);
    Entry& e = cells_[key];
    e.image = std::move(image);
    e.lru = lru_.begin();
    stats_.resident = cells_.size();
    return e.image;
}

}  // namespace throng
