#include "throng/render/MorphCache.h"

#include <stdexcept>
#include <string>

#include "throng/render/GpuMorpher.h"
#include "throng/scenegraph/Stopwatch.h"

namespace throng {

Image morphDroppedCell(const ImpostorAtlas& atlas, std::uint32_t view, int keyframe, const MorphCacheOptions& options,
                       GpuMorpher* gpu) {
    if (keyframe < 0 || keyframe >= atlas.keyframeCount() || view >= atlas.views().viewCount())
        throw std::invalid_argument("morphDroppedCell: view " + std::to_string(view) + " key-frame " +
                                    std::to_string(keyframe) + " out of range");
    int before = 0, after = 0;
    float t = 0.5f;
    atlas.neighbours(keyframe, before, after, t);
    const std::vector<std::uint32_t> bones = atlas.strongestBones(options.features);
    std::vector<FeatureLine> from, to, target;
    for (std::uint32_t b : bones) {
        from.push_back(atlas.lines(view, before)[b]);
        to.push_back(atlas.lines(view, after)[b]);
        target.push_back(atlas.lines(view, keyframe)[b]);
    }
    if (!options.skeletonTargets) interpolateLines(from, to, t, target);
    const Image a = atlas.cell(view, before), b = atlas.cell(view, after);
    return gpu ? gpu->morph(a, from, b, to, target, t, options.parameters)
               : morphImages(a, from, b, to, target, t, options.parameters, options.threads);
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
