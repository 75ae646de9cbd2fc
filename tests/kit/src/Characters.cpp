#include "throng/testkit/Characters.h"

#include <map>

#include "throng/testkit/Assets.h"

namespace throng::testkit {

const CharacterAsset& sharedCharacter(const std::string& file) {
    static std::map<std::string, CharacterAsset> loaded;
    auto it = loaded.find(file);
    if (it == loaded.end()) it = loaded.emplace(file, loadCharacter(characterPath(file))).first;
    return it->second;
}

}  // namespace throng::testkit
