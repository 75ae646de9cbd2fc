#pragma once
// One character found in a glTF file: the template built from a skin (or from the unskinned meshes)
// and how its parts map back to the file, for tools and for tests.

#include <memory>
#include <vector>

#include "throng/actors/ActorTemplate.h"

namespace throng {

/// A template built from a glTF skin, or the rigid template of the unskinned meshes.
struct LoadedCharacter {
    std::shared_ptr<const ActorTemplate> tmpl;  ///< the template
    int skin = -1;                              ///< glTF skin index, or -1 for the rigid template
    std::vector<int> nodeSource;                ///< glTF node of each Skeleton node
    int jointCount = 0;                         ///< joints of the skin (Skeleton nodes with DOFs)
    std::vector<int> primitives;                ///< indices into CharacterAsset::primitives drawn by it
    std::vector<int> clipSource;                ///< glTF animation of each clip of the template
    /// Per vaLod level of the skinned mesh: the largest surface deviation its simplification
    /// made, in metres (0 for the full mesh): what each level's saving costs in accuracy.
    std::vector<double> lodErrors;
};

}  // namespace throng
