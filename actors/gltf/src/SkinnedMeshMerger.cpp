#include "SkinnedMeshMerger.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "throng/scenegraph/Image.h"

namespace throng::gltf {
namespace {

// Linear -> sRGB 8-bit, for palette textures built from base colours.
std::uint8_t toSrgb8(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    const double s = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(s * 255.0));
}

}  // namespace

std::shared_ptr<MeshData> mergeSkinnedPrimitives(GltfDocument& doc, const std::vector<ReadPrimitive>& primitives,
                                                 const std::vector<int>& which, const std::string& name,
                                                 const std::string& where) {
    auto merged = std::make_shared<MeshData>();
    merged->name = name;
    bool normals = true, eight = false;
    std::map<int, std::size_t> textureTriangles;
    std::vector<glm::vec4> colours;
    for (int i : which) {
        const MeshData& p = *primitives[static_cast<std::size_t>(i)].local;
        normals = normals && !p.normals.empty();
        eight = eight || !p.joints1.empty();
        if (primitives[static_cast<std::size_t>(i)].texture >= 0) textureTriangles[primitives[static_cast<std::size_t>(i)].texture] += p.triangleCount();
        if (std::find(colours.begin(), colours.end(), p.baseColor) == colours.end()) colours.push_back(p.baseColor);
    }
    int chosen = -1;
    std::size_t best = 0;
    for (const auto& [img, tris] : textureTriangles)
        if (tris > best) best = tris, chosen = img;
    if (textureTriangles.size() > 1)
        doc.warn(where, std::to_string(textureTriangles.size()) + " textures on one skinned mesh: image " +
                            std::to_string(chosen) + " (most triangles) kept for all");
    const bool palette = chosen < 0 && colours.size() > 1;
    std::shared_ptr<Image> paletteImage;
    if (palette) {
        paletteImage = std::make_shared<Image>();
        paletteImage->name = merged->name + "/palette";
        paletteImage->width = static_cast<int>(colours.size());
        paletteImage->height = 1;
        for (const glm::vec4& c : colours)
            paletteImage->rgba.insert(paletteImage->rgba.end(), {toSrgb8(c.r), toSrgb8(c.g), toSrgb8(c.b),
                                                                 static_cast<std::uint8_t>(std::lround(std::clamp(c.a, 0.0f, 1.0f) * 255))});
        merged->baseColorTexture = paletteImage;
    }
    for (int i : which) {
        const ReadPrimitive& pr = primitives[static_cast<std::size_t>(i)];
        const MeshData& p = *pr.local;
        const auto base = static_cast<std::uint32_t>(merged->positions.size());
        merged->positions.insert(merged->positions.end(), p.positions.begin(), p.positions.end());
        if (normals) merged->normals.insert(merged->normals.end(), p.normals.begin(), p.normals.end());
        for (std::uint32_t k : p.indices) merged->indices.push_back(base + k);
        merged->joints0.insert(merged->joints0.end(), p.joints0.begin(), p.joints0.end());
        merged->weights0.insert(merged->weights0.end(), p.weights0.begin(), p.weights0.end());
        if (eight) {
            if (p.joints1.empty()) {
                merged->joints1.insert(merged->joints1.end(), p.vertexCount(), glm::u16vec4(0));
                merged->weights1.insert(merged->weights1.end(), p.vertexCount(), glm::vec4(0));
            } else {
                merged->joints1.insert(merged->joints1.end(), p.joints1.begin(), p.joints1.end());
                merged->weights1.insert(merged->weights1.end(), p.weights1.begin(), p.weights1.end());
            }
        }
        if (palette) {
            const auto c = static_cast<float>(std::find(colours.begin(), colours.end(), p.baseColor) - colours.begin());
            merged->texcoords.insert(merged->texcoords.end(), p.vertexCount(), glm::vec2((c + 0.5f) / float(colours.size()), 0.5f));
        } else if (chosen >= 0) {
            if (pr.texture == chosen) merged->texcoords.insert(merged->texcoords.end(), p.texcoords.begin(), p.texcoords.end());
            else merged->texcoords.insert(merged->texcoords.end(), p.vertexCount(), glm::vec2(0.0f));
            merged->baseColorTexture = p.baseColorTexture && pr.texture == chosen ? p.baseColorTexture : merged->baseColorTexture;
        }
    }
    if (!palette && !which.empty()) {
        // The colour of the chosen texture's primitive, or the single colour.
        for (int i : which)
            if (chosen < 0 || primitives[static_cast<std::size_t>(i)].texture == chosen) {
                merged->baseColor = primitives[static_cast<std::size_t>(i)].local->baseColor;
                break;
            }
    }
    if (chosen >= 0 && !merged->baseColorTexture) merged->texcoords.clear();
    // Morph targets by name: a primitive without one of them adds zero offsets for it.
    for (int i : which)
        for (const MorphTarget& t : primitives[static_cast<std::size_t>(i)].local->morphTargets)
            if (merged->findMorphTarget(t.name) < 0) {
                MorphTarget m;
                m.name = t.name;
                m.defaultWeight = t.defaultWeight;
                merged->morphTargets.push_back(std::move(m));
            }
    for (MorphTarget& m : merged->morphTargets) {
        bool anyNormals = false;
        for (int i : which) {
            const MeshData& p = *primitives[static_cast<std::size_t>(i)].local;
            const int k = p.findMorphTarget(m.name);
            anyNormals = anyNormals || (k >= 0 && !p.morphTargets[static_cast<std::size_t>(k)].normals.empty());
        }
        anyNormals = anyNormals && normals;
        for (int i : which) {
            const MeshData& p = *primitives[static_cast<std::size_t>(i)].local;
            const int k = p.findMorphTarget(m.name);
            const MorphTarget* t = k >= 0 ? &p.morphTargets[static_cast<std::size_t>(k)] : nullptr;
            if (t) m.positions.insert(m.positions.end(), t->positions.begin(), t->positions.end());
            else m.positions.insert(m.positions.end(), p.vertexCount(), glm::vec3(0.0f));
            if (!anyNormals) continue;
            if (t && !t->normals.empty()) m.normals.insert(m.normals.end(), t->normals.begin(), t->normals.end());
            else m.normals.insert(m.normals.end(), p.vertexCount(), glm::vec3(0.0f));
        }
    }
    return merged;
}


}  // namespace throng::gltf
