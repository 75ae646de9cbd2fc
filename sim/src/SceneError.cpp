#include "throng/sim/SceneError.h"

namespace throng::sim {

SceneError::SceneError(std::string file, std::string path, std::string reason)
    : std::runtime_error(file + ": " + (path.empty() ? std::string("(document)") : path) + ": " + reason),
      file_(std::move(file)),
      path_(std::move(path)),
      reason_(std::move(reason)) {}

}  // namespace throng::sim
