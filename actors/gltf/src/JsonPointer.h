#pragma once
// Internal: JSON pointers into a glTF document, the "where" of every GltfError and warning.

#include <cstddef>
#include <string>

namespace throng::gltf {

/// Element `i` of the array at pointer `array`: ptr("/skins", 2) is "/skins/2".
inline std::string ptr(const std::string& array, std::size_t i) { return array + "/" + std::to_string(i); }

}  // namespace throng::gltf
