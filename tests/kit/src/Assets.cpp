// The paths come from the build (CMake knows where the repository is); see Assets.h.
#include "throng/testkit/Assets.h"

namespace throng::testkit {

std::string sharedAssets() { return THRONG_SHARED_ASSETS; }

std::string assetPath(const std::string& relative) { return sharedAssets() + "/" + relative; }

std::string characterPath(const std::string& file) { return assetPath("characters/" + file); }

std::string townDefaultScene() { return THRONG_TOWN_DEFAULT_SCENE; }

}  // namespace throng::testkit
