#pragma once
// vaLod (seed 002 §5.1): the levels of detail of one piece of an actor, chosen by the actor's single
// eye distance instead of a distance of its own. Levels are ordered from the highest detail.

#include <memory>
#include <vector>

#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/Drawable.h"

namespace throng {

/// One level: `drawable` (or nothing, if null) shown while the distance is below `maxDistance`.
struct VaLodLevel {
    double maxDistance = 0.0;                  ///< end of this level's range (metres, > previous)
    std::shared_ptr<const Drawable> drawable;  ///< what the level shows, or null for nothing
    int skin = -1;                             ///< template skin deforming it (a skinned mesh), or -1 (rigid)
};

/// Levels of detail selected by an actor's eye distance.
class VaLod {
public:
    /// Appends a level, deformed by template skin `skin` (-1: rigid). Throws std::invalid_argument
    /// if maxDistance is not positive (infinity is allowed) or not above the previous level's.
    void addLevel(double maxDistance, std::shared_ptr<const Drawable> drawable, int skin = -1);
    /// The levels, highest detail first.
    const std::vector<VaLodLevel>& levels() const { return levels_; }
    /// Whether there is no level.
    bool empty() const { return levels_.empty(); }
    /// Index of the level shown at `distance` (already scaled by LOD bias and priority), or -1.
    int select(double distance) const {
        for (std::size_t i = 0; i < levels_.size(); ++i)
            if (distance < levels_[i].maxDistance) return static_cast<int>(i);
        return -1;
    }
    /// Index of the level shown at the distance whose square is `distance2`, or -1 (what LOD
    /// decisions use, to avoid a square root).
    int selectSquared(double distance2) const {
        for (std::size_t i = 0; i < levels_.size(); ++i)
            if (distance2 < levels_[i].maxDistance * levels_[i].maxDistance) return static_cast<int>(i);
        return -1;
    }
    /// Distance beyond which nothing is shown (0 when empty).
    double lastDistance() const { return levels_.empty() ? 0.0 : levels_.back().maxDistance; }
    /// Distance beyond which no drawable is shown (levels with a null drawable do not count).
    double lastDrawnDistance() const;
    /// Sphere holding every rigid level's drawable, in the frame they are drawn in (empty if none).
    /// Skinned levels move with their joints and are bounded by the joints' spheres instead.
    BoundingSphere bound() const;

private:
    std::vector<VaLodLevel> levels_;
};

}  // namespace throng
