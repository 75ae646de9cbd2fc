// The glTF character loader: parse and check the document (GltfDocument), read and check what it
// holds (ContentReader), then build one template per skin (SkinTemplateBuilder) and one for the
// unskinned meshes (buildStaticTemplate). See GltfLoader.h.

#include "throng/gltf/GltfLoader.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "ContentReader.h"
#include "GltfDocument.h"
#include "SkinTemplateBuilder.h"
#include "StaticTemplateBuilder.h"

namespace throng {
namespace gltf {
namespace {

// Rejects a scale or LOD levels that make no sense, before any work.
void checkOptions(const GltfDocument& doc, const GltfLoadOptions& options) {
    if (!(std::isfinite(options.scale) && options.scale > 0.0))
        doc.fail("/", "GltfLoadOptions::scale must be a positive number, got " + std::to_string(options.scale));
    if (!(options.jointMinAngle >= 0.0 && options.jointMinAngle < 1.0))
        doc.fail("/", "GltfLoadOptions::jointMinAngle must be in [0, 1) radians, got " + std::to_string(options.jointMinAngle));
    double previous = 0.0;
    for (std::size_t i = 0; i < options.lodLevels.size(); ++i) {
        const GltfLodLevel& l = options.lodLevels[i];
        const std::string which = "GltfLoadOptions::lodLevels[" + std::to_string(i) + "]";
        if (!(l.maxDistance > previous)) doc.fail("/", which + ": maxDistance must exceed the previous level's (" + std::to_string(previous) + ")");
        if (!(l.triangleShare > 0.0 && l.triangleShare <= 1.0)) doc.fail("/", which + ": triangleShare must be in (0, 1]");
        previous = l.maxDistance;
    }
}

// The name of the templates of a file: its name without directory and extension.
std::string stem(const std::string& path) {
    const std::string s = std::filesystem::path(path).stem().string();
    return s.empty() ? path : s;
}

// Loads the document in `bytes`: parsed, read and checked, then its templates (named after `name`).
CharacterAsset load(const std::vector<std::uint8_t>& bytes, const std::string& file, const std::string& name,
                    const std::string& baseDirectory, const GltfLoadOptions& options) {
    GltfDocument doc = parseDocument(bytes, file, baseDirectory, options);
    CharacterAsset asset;
    asset.source = doc.file;
    checkOptions(doc, options);
    const GltfContent content = ContentReader(doc, options, asset).read();
    std::set<int> rigidClaimed;  // unskinned primitives drawn as a joint's rigid geometry
    std::vector<std::set<int>> loadedChannels(content.channels.size());
    for (std::size_t s = 0; s < doc.model.skins.size(); ++s) {
        SkinTemplate built = SkinTemplateBuilder(doc, content, asset.animations, options, name, static_cast<int>(s)).build();
        rigidClaimed.insert(built.rigidPrimitives.begin(), built.rigidPrimitives.end());
        for (const auto& [a, c] : built.channelsUsed) loadedChannels[static_cast<std::size_t>(a)].insert(c);
        asset.characters.push_back(std::move(built.character));
    }
    if (auto statics = buildStaticTemplate(doc, content, rigidClaimed, options, name)) asset.characters.push_back(std::move(*statics));
    for (std::size_t a = 0; a < loadedChannels.size(); ++a)
        asset.animations[a].channelsLoaded = static_cast<int>(loadedChannels[a].size());
    asset.warnings = doc.warnings;
    return asset;
}

}  // namespace
}  // namespace gltf

CharacterAsset loadCharacter(const std::string& path, const GltfLoadOptions& options) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (ec) throw GltfError(path, "/", "cannot read the file (" + ec.message() + ")");
    if (size > options.limits.maxFileBytes)
        throw GltfError(path, "/", "the file holds " + std::to_string(size) + " bytes, more than the limit of " +
                                       std::to_string(options.limits.maxFileBytes));
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    std::ifstream in(path, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
        throw GltfError(path, "/", "cannot read the file");
    std::string base = options.baseDirectory;
    if (base.empty()) {
        base = fs::path(path).parent_path().string();
        if (base.empty()) base = ".";
    }
    return gltf::load(bytes, path, gltf::stem(path), base, options);
}

CharacterAsset loadCharacterFromMemory(const std::vector<std::uint8_t>& bytes, const std::string& name,
                                       const GltfLoadOptions& options) {
    return gltf::load(bytes, name, gltf::stem(name), options.baseDirectory, options);
}

}  // namespace throng
