#pragma once
// A line of text tied to a point of the world: what a speaker says, shown above its head.

#include <string>

#include "throng/scenegraph/Math.h"

namespace throng {

/// Text shown centred just above `position` (world coordinates) as the frame's camera sees it.
struct Caption {
    Vec3 position{0.0};  ///< the point the text stands above (a head's top)
    std::string text;    ///< one line
};

}  // namespace throng
