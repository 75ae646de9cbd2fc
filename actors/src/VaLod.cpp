#include "throng/actors/VaLod.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace throng {

void VaLod::addLevel(double maxDistance, std::shared_ptr<const Drawable> drawable, int skin) {
    if (std::isnan(maxDistance) || maxDistance <= 0.0)
        throw std::invalid_argument("VaLod::addLevel: argument 'maxDistance' must be positive, got " +
                                    std::to_string(maxDistance));
    if (!levels_.empty() && maxDistance <= levels_.back().maxDistance)
        throw std::invalid_argument("VaLod::addLevel: argument 'maxDistance' (" + std::to_string(maxDistance) +
                                    ") must exceed the previous level's (" +
                                    std::to_string(levels_.back().maxDistance) + ")");
    if (skin < -1) throw std::invalid_argument("VaLod::addLevel: argument 'skin' must be -1 or a skin index");
    levels_.push_back({maxDistance, std::move(drawable), skin});
}

double VaLod::lastDrawnDistance() const {
    double d = 0.0;
    for (const VaLodLevel& l : levels_)
        if (l.drawable) d = l.maxDistance;
    return d;
}

BoundingSphere VaLod::bound() const {
    BoundingSphere b;
    for (const VaLodLevel& l : levels_)
        if (l.drawable && l.skin < 0) b.expandBy(l.drawable->localBound());
    return b;
}

}  // namespace throng
