#pragma once
// An error in a scene file, with the JSON path of the offending value (for example
// "/actors/2/count") and the reason.

#include <stdexcept>
#include <string>

namespace throng::sim {

/// A scene file that cannot be used.
class SceneError : public std::runtime_error {
public:
    /// An error at `path` (JSON Pointer syntax, "" for the whole document) for `reason`.
    SceneError(std::string file, std::string path, std::string reason);
    /// The file (or "<text>").
    const std::string& file() const { return file_; }
    /// JSON Pointer to the offending value.
    const std::string& path() const { return path_; }
    /// Why it is wrong.
    const std::string& reason() const { return reason_; }

private:
    std::string file_, path_, reason_;
};

}  // namespace throng::sim
