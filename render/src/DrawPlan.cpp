// The CPU half of GlRenderer::draw (DrawPlan.h).
#include "DrawPlan.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/matrix.hpp>

#include "throng/scenegraph/Drawable.h"

namespace throng::detail {

std::int32_t distanceBand(float distance) {
    if (!(distance >= 16.0f)) return 0;
    return 1 + static_cast<std::int32_t>(std::log2(std::min(distance, 1e30f) / 16.0f));
}

void DrawOrder::plan(std::span<const DrawItem* const> items, const Vec3& eye, bool frontToBack) {
    order_.resize(items.size());
    band_.assign(items.size(), 0);
    if (!frontToBack) {
        for (std::size_t i = 0; i < items.size(); ++i) order_[i] = static_cast<std::uint32_t>(i);
        return;
    }
    byDistance_.resize(items.size());
    for (std::size_t i = 0; i < items.size(); ++i) {
        const DrawItem& item = *items[i];
        float key = 0.0f;
        if (item.drawable) {
            const glm::dmat3 l(item.world.linear);
            const BoundingSphere& b = item.drawable->localBound();
            const Vec3 centre = item.world.transformPoint(b.center());
            const double scale = std::sqrt(std::max({glm::dot(l[0], l[0]), glm::dot(l[1], l[1]), glm::dot(l[2], l[2])}));
            key = static_cast<float>(std::max(glm::length(centre - eye) - b.radius() * scale, 0.0));
            if (std::isnan(key)) key = 0.0f;  // a NaN would break the sort's ordering
        }
        byDistance_[i] = {key, static_cast<std::uint32_t>(i)};
        band_[i] = distanceBand(key);
    }
    std::stable_sort(byDistance_.begin(), byDistance_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < items.size(); ++i) order_[i] = byDistance_[i].second;
}

void BatchPlanner::begin(bool instancing) {
    batches_.clear();
    ++stamp_;
    instancing_ = instancing;
}

std::uint32_t BatchPlanner::join(BatchSlots& slots, int variant, std::int32_t band, bool& opened) {
    if (slots.stamp != stamp_) {
        slots.stamp = stamp_;
        std::fill(std::begin(slots.batch), std::end(slots.batch), kNoBatch);
    }
    std::uint32_t& b = slots.batch[variant];
    opened = b == kNoBatch || !instancing_ || batches_[b].band != band;
    if (opened) {
        b = static_cast<std::uint32_t>(batches_.size());
        batches_.push_back(Batch{0, 0, 0, band});
    }
    ++batches_[b].count;
    return b;
}

std::uint32_t BatchPlanner::alone(std::int32_t band) {
    batches_.push_back(Batch{1, 0, 0, band});
    return static_cast<std::uint32_t>(batches_.size() - 1);
}

std::uint32_t BatchPlanner::layOut() {
    std::uint32_t slots = 0;
    for (Batch& b : batches_) {
        b.first = slots;
        b.filled = 0;
        slots += b.count;
    }
    return slots;
}

void writeInstance(InstanceData& d, const DrawItem& item, const Vec3& eye) {
    // The linear part as it is (already float), the translation made eye-relative in double.
    const glm::mat3& l = item.world.linear;
    for (int c = 0; c < 3; ++c) {
        d.model[4 * c + 0] = l[c].x;
        d.model[4 * c + 1] = l[c].y;
        d.model[4 * c + 2] = l[c].z;
        d.model[4 * c + 3] = 0.0f;
    }
    const Vec3 t = item.world.translation - eye;
    d.model[12] = static_cast<float>(t.x);
    d.model[13] = static_cast<float>(t.y);
    d.model[14] = static_cast<float>(t.z);
    d.model[15] = 1.0f;
    std::memcpy(d.tint, &item.tint[0], sizeof d.tint);
    std::memcpy(d.look, item.look.rgba.data(), sizeof d.look);
    d.paletteBase = 0;
    d.row1Base = 0;
    d.blend = 0.0f;
    d.pad = 0;
}

}  // namespace throng::detail
