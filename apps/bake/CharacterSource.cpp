#include "CharacterSource.h"

#include <stdexcept>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SeedHumanoid.h"
// The glTF loader is written on its own branch; the tools use it as soon as it is there.
#if __has_include("throng/actors/GltfLoader.h")
#include "throng/actors/GltfLoader.h"
#define THRONG_BAKE_HAS_GLTF 1
#else
#define THRONG_BAKE_HAS_GLTF 0
#endif

namespace throng::bake {

std::shared_ptr<const ActorTemplate> loadTemplate(const std::string& source) {
    if (source == "seed-humanoid") return makeSeedHumanoid();
#if THRONG_BAKE_HAS_GLTF
    std::shared_ptr<const ActorTemplate> tmpl = loadCharacter(source).primaryTemplate();
    if (!tmpl) throw std::runtime_error("'" + source + "' holds no character");
    return tmpl;
#else
    throw std::runtime_error("cannot load '" + source + "': this build has no glTF loader (use seed-humanoid)");
#endif
}

int findClipOrThrow(const ActorTemplate& tmpl, const std::string& name) {
    if (tmpl.clips().empty()) throw std::runtime_error("template '" + tmpl.name() + "' has no clip");
    if (name.empty()) return 0;
    const int i = tmpl.findClip(name);
    if (i >= 0) return i;
    std::string known;
    for (const auto& c : tmpl.clips()) known += (known.empty() ? "" : ", ") + c->name();
    throw std::runtime_error("template '" + tmpl.name() + "' has no clip '" + name + "' (its clips: " + known + ")");
}

}  // namespace throng::bake
