#include "throng/gltf/CharacterAsset.h"

namespace throng {

std::shared_ptr<const ActorTemplate> CharacterAsset::primaryTemplate() const {
    for (const LoadedCharacter& c : characters)
        if (c.skin >= 0) return c.tmpl;
    return characters.empty() ? nullptr : characters.front().tmpl;
}

const LoadedCharacter* CharacterAsset::findCharacter(const std::string& name) const {
    for (const LoadedCharacter& c : characters)
        if (c.tmpl && c.tmpl->name() == name) return &c;
    return nullptr;
}

}  // namespace throng
