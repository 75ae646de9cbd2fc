#pragma once
// The one exception the glTF loader throws: which file, where in it (a JSON pointer into the glTF
// document, so a user can find the culprit in any editor) and what is wrong, on one line.

#include <stdexcept>
#include <string>

namespace throng {

/// A glTF file that cannot be loaded; what() is "file: where: problem".
class GltfError : public std::invalid_argument {
public:
    /// An error in `file` at JSON pointer `where` (e.g. "/skins/0/joints/2", "/" for the whole file).
    GltfError(std::string file, std::string where, std::string problem);
    /// The file (path, or the name given to loadCharacterFromMemory).
    const std::string& file() const { return file_; }
    /// JSON pointer to the offending value.
    const std::string& where() const { return where_; }
    /// What is wrong with it.
    const std::string& problem() const { return problem_; }

private:
    std::string file_, where_, problem_;
};

}  // namespace throng
