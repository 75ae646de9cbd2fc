// Whether the ranks of a run would build the same world (RankAgreement.h).

#include "RankAgreement.h"

#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string_view>

namespace throng::town {
namespace {

std::string optionValue(std::int64_t value, bool given) { return given ? std::to_string(value) : "not given"; }

}  // namespace

WorldKey worldKey(const TownOptions& o) {
    WorldKey key;
    std::ifstream in(o.scene, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw std::runtime_error("cannot read the scene file " + o.scene);
    key.sceneHash = std::hash<std::string_view>{}(text);  // one build on every rank: one hash function
    key.sceneBytes = text.size();
    key.actors = o.actors.value_or(-1);
    key.seedGiven = o.seed.has_value();
    key.seed = o.seed.value_or(0);
    key.frames = o.frames;
    key.poseOnRanks = o.poseOnRanks;
    key.looks = o.looks;
    key.faces = o.faces;
    return key;
}

std::optional<std::string> disagreement(const WorldKey& mine, const WorldKey& root, const std::string& scene) {
    std::string what;
    auto add = [&](const std::string& part) { what += (what.empty() ? "" : "; ") + part; };
    if (mine.sceneHash != root.sceneHash || mine.sceneBytes != root.sceneBytes)
        add("its scene file " + scene + " (" + std::to_string(mine.sceneBytes) + " bytes) is not rank 0's (" +
            std::to_string(root.sceneBytes) + " bytes, other contents)");
    if (mine.actors != root.actors)
        add("--actors " + optionValue(mine.actors, mine.actors >= 0) + " here, " + optionValue(root.actors, root.actors >= 0) + " on rank 0");
    if (mine.seedGiven != root.seedGiven || mine.seed != root.seed)
        add("--seed " + (mine.seedGiven ? std::to_string(mine.seed) : std::string("not given")) + " here, " +
            (root.seedGiven ? std::to_string(root.seed) : std::string("not given")) + " on rank 0");
    if (mine.frames != root.frames) add("--frames " + std::to_string(mine.frames) + " here, " + std::to_string(root.frames) + " on rank 0");
    auto flag = [&](const char* name, std::uint8_t here, std::uint8_t there) {
        if (here != there) add(std::string(name) + (here ? " on" : " off") + " here, " + (there ? "on" : "off") + " on rank 0");
    };
    flag("--pose-on-ranks", mine.poseOnRanks, root.poseOnRanks);
    flag("--looks", mine.looks, root.looks);
    flag("--faces", mine.faces, root.faces);
    if (what.empty()) return std::nullopt;
    return "this rank would build or step another world than rank 0: " + what +
           ". Every rank must read the same scene file with the same --actors, --seed, --frames, --pose-on-ranks, --looks and --faces";
}

}  // namespace throng::town
