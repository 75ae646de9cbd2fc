#pragma once
// Internal: a glTF document parsed by tinygltf after our own checks of what tinygltf trusts (GLB
// chunk sizes, JSON nesting, buffer sources, skin arrays) and with our own file and image callbacks
// (external files confined to the base directory and size limits; images kept encoded until a
// primitive needs them).

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "throng/gltf/GltfLoadOptions.h"

namespace throng::gltf {

/// A parsed document: the tinygltf model, plus what our checks found.
struct GltfDocument {
    std::string file;                   ///< name for messages
    bool binary = false;                ///< read from a GLB container
    tinygltf::Model model;              ///< images hold their encoded bytes (component = 0)
    std::vector<std::string> warnings;  ///< "where: problem"

    /// Throws GltfError for this file: `problem` at JSON pointer `where`.
    [[noreturn]] void fail(const std::string& where, const std::string& problem) const;
    /// Records "where: problem" among the warnings (something skipped or fixed).
    void warn(const std::string& where, const std::string& problem) { warnings.push_back(where + ": " + problem); }
};

/// Parses `bytes` (glTF JSON or GLB). Throws GltfError with the JSON pointer of the problem.
GltfDocument parseDocument(const std::vector<std::uint8_t>& bytes, const std::string& file,
                           const std::string& baseDirectory, const GltfLoadOptions& options);

}  // namespace throng::gltf
