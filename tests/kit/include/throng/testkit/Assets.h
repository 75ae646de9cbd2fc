#pragma once
// Where the tests and benchmarks find their input: the third-party assets beside the repository
// (../shared/assets, with their licences) and the town's default scene file. One place, so a
// moved asset folder is changed once.

#include <string>

namespace throng::testkit {

/// The shared assets folder (characters/, town/, malformed/ ...), without a trailing slash.
std::string sharedAssets();
/// A file under the shared assets, e.g. assetPath("town/kenney_city_builder").
std::string assetPath(const std::string& relative);
/// A glTF character of the shared assets, e.g. characterPath("CesiumMan.glb").
std::string characterPath(const std::string& file);
/// The scene file throng-town runs by default (the town the frame-level benchmarks measure).
std::string townDefaultScene();

}  // namespace throng::testkit
