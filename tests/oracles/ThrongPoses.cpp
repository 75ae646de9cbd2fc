#include "ThrongPoses.h"

#include <algorithm>
#include <map>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "throng/testkit/Assets.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/render/CpuSkinning.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng::test {

std::string characterPath(const std::string& file) { return testkit::sharedAssets() + "/characters/" + file; }

const CharacterAsset& loadedCharacter(const std::string& file, double scale) {
    static std::map<std::pair<std::string, double>, CharacterAsset> cache;
    auto it = cache.find({file, scale});
    if (it == cache.end()) {
        GltfLoadOptions options;
        options.scale = scale;
        it = cache.emplace(std::pair{file, scale}, loadCharacter(characterPath(file), options)).first;
    }
    return it->second;
}

std::vector<glm::dvec3> drawnPositions(const DrawList& list, std::span<const glm::mat4> palette) {
    std::vector<glm::dvec3> out;
    bool replaced = palette.empty();
    for (const DrawItem& item : list.items()) {
        const auto* drawable = dynamic_cast<const MeshDrawable*>(item.drawable);
        if (!drawable) throw std::invalid_argument("drawnPositions: a draw item is not a MeshDrawable");
        const MeshData& mesh = drawable->mesh();
        std::vector<glm::vec3> positions(mesh.positions);
        if (item.skinPalette) {
            std::span<const glm::mat4> used(item.skinPalette, item.skinPaletteSize);
            if (!replaced) used = palette, replaced = true;
            skinMesh(mesh, used, positions, {});
        }
        for (const glm::vec3& p : positions) out.emplace_back(item.world.toMat4() * Vec4(Vec3(p), 1.0));
    }
    return out;
}

std::uint32_t busiestJoint(const MeshData& mesh) {
    std::map<std::uint32_t, std::size_t> dominated;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const glm::vec4& w = mesh.weights0[v];
        const int c = int(std::max_element(&w[0], &w[0] + 4) - &w[0]);
        ++dominated[mesh.joints0[v][c]];
    }
    return std::max_element(dominated.begin(), dominated.end(),
                            [](const auto& a, const auto& b) { return a.second < b.second; })
        ->first;
}

glm::mat4 rotatedAboutJoint(const glm::mat4& entry, const glm::mat4& inverseBind, double angle, const glm::dvec3& axis) {
    const glm::dmat4 jointToModel = glm::dmat4(entry) * glm::inverse(glm::dmat4(inverseBind));
    const glm::dvec3 origin(jointToModel[3]);
    glm::dmat4 turn = glm::translate(glm::dmat4(1.0), origin);
    turn = glm::rotate(turn, angle, glm::normalize(axis));
    turn = glm::translate(turn, -origin);
    return glm::mat4(turn * glm::dmat4(entry));
}

}  // namespace throng::test
