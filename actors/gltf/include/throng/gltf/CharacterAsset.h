#pragma once
// Everything the glTF loader made of one file: one template per skin (plus one for the unskinned
// meshes), every primitive ready to draw, the animations and the warnings about what was skipped.

#include <memory>
#include <string>
#include <vector>

#include "throng/actors/ActorTemplate.h"
#include "throng/gltf/LoadedAnimation.h"
#include "throng/gltf/LoadedCharacter.h"
#include "throng/gltf/LoadedPrimitive.h"

namespace throng {

/// The result of loading a glTF file.
struct CharacterAsset {
    std::string source;                          ///< the file (or the name given for memory)
    std::vector<LoadedCharacter> characters;     ///< skinned templates first, then the rigid one
    std::vector<LoadedPrimitive> primitives;     ///< every primitive instance of the default scene
    std::vector<LoadedAnimation> animations;     ///< every animation of the file
    std::vector<std::string> warnings;           ///< "where: problem" for each thing skipped or fixed

    /// The template an application most likely wants: the first skinned one, else the rigid one,
    /// else null.
    std::shared_ptr<const ActorTemplate> primaryTemplate() const;
    /// The character whose template is named `name`, or null.
    const LoadedCharacter* findCharacter(const std::string& name) const;
};

}  // namespace throng
