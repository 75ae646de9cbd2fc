#pragma once
// Where the impostor tools get a character: a glTF file through the loader (when the build has
// it), or a procedural template by name ("seed-humanoid") so that the tools run without assets.

#include <memory>
#include <string>

namespace throng {
class ActorTemplate;
}

namespace throng::bake {

/// The template of `source`: "seed-humanoid", or a .glb/.gltf file (its primary character).
/// Throws std::runtime_error naming the source when it cannot be loaded or this build has no
/// glTF loader.
std::shared_ptr<const ActorTemplate> loadTemplate(const std::string& source);

/// Index of the clip named `name` in `tmpl` (the first clip when `name` is empty). Throws
/// std::runtime_error listing the template's clips when there is no such clip.
int findClipOrThrow(const ActorTemplate& tmpl, const std::string& name);

}  // namespace throng::bake
