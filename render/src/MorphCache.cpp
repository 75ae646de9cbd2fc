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
    DroppedCellLines c;
    atlas.neighbours(keyframe, c.before, c.after, c.t);
    const std::vector<std::uint32_t> bones = atlas.strongestBones(options.features);
    for (std::uint32_t b : bones) {
        c.from.push_back(atlas.lines(view, c.before)[b]);
        c.to.push_back(atlas.lines(view, c.after)[b]);
        c.target.push_back(atlas.lines(view, keyframe)[b]);
    }
    if (!options.skeletonTargets) interpolateLines(c.from, c.to, c.t, c.target);
    return c;
}

Image morphDroppedCell(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe, const MorphCacheOptions& options,
                       GpuMorpher* gpu) {
    const DroppedCellLines c = droppedCellLines(atlas, view, keyframe, options);
    const Image a = atlas.cell(view, c.before), b = atlas.cell(view, c.after);
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
    if (keyframe < 0 || keyframe >= atlas.keyframeCount() || atlas.stored(keyframe))
        throw std::invalid_argument("MorphCache::request: key-frame " + std::to_string(keyframe) + " is not a dropped one");
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
