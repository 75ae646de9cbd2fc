#include "throng/gltf/GltfError.h"

namespace throng {

GltfError::GltfError(std::string file, std::string where, std::string problem)
    : std::invalid_argument(file + ": " + where + ": " + problem),
      file_(std::move(file)),
      where_(std::move(where)),
      problem_(std::move(problem)) {}

}  // namespace throng
