#include "throng/support/CharacterSource.h"

#include <stdexcept>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/gltf/GltfLoader.h"

namespace throng::support {

std::shared_ptr<const ActorTemplate> loadTemplate(const std::string& source) {
    if (source == kSeedHumanoid) return makeSeedHumanoid();
    std::shared_ptr<const ActorTemplate> tmpl = loadCharacter(source).primaryTemplate();
    if (!tmpl) throw std::runtime_error("'" + source + "' holds no character");
    return tmpl;
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

}  // namespace throng::support
