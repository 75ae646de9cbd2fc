#pragma once
// Summary of one glTF animation: how much of it the loader could turn into clips.

#include <string>

namespace throng {

/// One glTF animation.
struct LoadedAnimation {
    std::string name;        ///< its name (or "animation<i>" when unnamed)
    double duration = 0.0;   ///< last key time, seconds
    int channels = 0;        ///< channels in the file
    int channelsLoaded = 0;  ///< channels that drive a joint of a loaded template
};

}  // namespace throng
