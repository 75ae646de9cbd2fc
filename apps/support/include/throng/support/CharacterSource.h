#pragma once
// Where the tools get a character: a glTF file through the loader (throng::gltf), or a
// procedural template by name ("seed-humanoid") so that the tools run without assets.

#include <memory>
#include <string>

namespace throng {
class ActorTemplate;
}

namespace throng::support {

/// The name of the procedural figure every tool accepts in place of a file.
inline constexpr const char* kSeedHumanoid = "seed-humanoid";

/// The template of `source`: "seed-humanoid", or a .glb/.gltf file (its primary character).
/// Throws throng::GltfError (file, JSON pointer, problem) when the file cannot be loaded, and
/// std::runtime_error naming the source when it holds no character.
std::shared_ptr<const ActorTemplate> loadTemplate(const std::string& source);

/// Index of the clip named `name` in `tmpl` (the first clip when `name` is empty). Throws
/// std::runtime_error listing the template's clips when there is no such clip.
int findClipOrThrow(const ActorTemplate& tmpl, const std::string& name);

}  // namespace throng::support
