#include "throng/render/ProceduralMeshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

namespace throng {
namespace {

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument("makeSkinnedTube: " + what); }

}  // namespace

std::shared_ptr<MeshData> makeQuad(float width, float height, std::shared_ptr<const Image> texture, const glm::vec4& color) {
    if (!(width > 0 && height > 0)) throw std::invalid_argument("makeQuad: width and height must be positive and finite");
    auto mesh = std::make_shared<MeshData>();
    mesh->name = "quad";
    mesh->baseColor = color;
    mesh->baseColorTexture = std::move(texture);
    const float w = 0.5f * width, h = 0.5f * height;
    mesh->positions = {{-w, -h, 0}, {w, -h, 0}, {w, h, 0}, {-w, h, 0}};
    mesh->normals.assign(4, glm::vec3(0, 0, 1));
    mesh->texcoords = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    mesh->indices = {0, 1, 2, 0, 2, 3};
    return mesh;
}

std::shared_ptr<Image> makeCheckerImage(int size, int cells, const glm::u8vec4& a, const glm::u8vec4& b) {
    if (size <= 0 || cells <= 0 || cells > size)
        throw std::invalid_argument("makeCheckerImage: need 0 < cells <= size, got size " + std::to_string(size) +
                                    " and cells " + std::to_string(cells));
    auto image = std::make_shared<Image>();
    image->name = "checker";
    image->width = image->height = size;
    image->rgba.resize(static_cast<std::size_t>(size) * size * 4);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::u8vec4& c = ((x * cells / size) + (y * cells / size)) % 2 == 0 ? a : b;
            std::uint8_t* p = &image->rgba[(static_cast<std::size_t>(y) * size + x) * 4];
            p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = c.a;
        }
    return image;
}

SkinnedTubeOptions cesiumManSizedTube() {
    SkinnedTubeOptions o;
    o.joints = 19;
    o.bands = 48;
    o.ringsPerBand = 4;
    o.segments = 16;
    o.height = 1.8f;
    o.radius = 0.15f;
    return o;
}

std::shared_ptr<MeshData> makeSkinnedTube(const SkinnedTubeOptions& o) {
    if (o.joints < 1 || o.joints > 65535) bad("joints must be 1-65535, got " + std::to_string(o.joints));
    if (o.bands < 1) bad("bands must be at least 1, got " + std::to_string(o.bands));
    if (o.ringsPerBand < 2) bad("ringsPerBand must be at least 2, got " + std::to_string(o.ringsPerBand));
    if (o.segments < 3) bad("segments must be at least 3, got " + std::to_string(o.segments));
    if (o.influences != 4 && o.influences != 8) bad("influences must be 4 or 8, got " + std::to_string(o.influences));
    if (!(o.radius > 0 && o.height > 0 && o.blend > 0 && std::isfinite(o.radius) && std::isfinite(o.height) &&
          std::isfinite(o.blend)))
        bad("radius, height and blend must be positive and finite");
    auto mesh = std::make_shared<MeshData>();
    mesh->name = "skinned tube";
    mesh->baseColor = o.color;
    const float bone = o.height / static_cast<float>(o.joints);
    const int ring = o.segments + 1;  // the seam vertex is duplicated for texture coordinates
    std::vector<std::pair<float, int>> weights(static_cast<std::size_t>(o.joints));
    for (int b = 0; b < o.bands; ++b) {
        const auto base = static_cast<std::uint32_t>(mesh->positions.size());
        for (int r = 0; r < o.ringsPerBand; ++r) {
            const float t = (static_cast<float>(b) + static_cast<float>(r) / static_cast<float>(o.ringsPerBand - 1)) /
                            static_cast<float>(o.bands);
            const float y = t * o.height;
            // Tent weights around each bone's middle; keep the largest `influences`.
            for (int j = 0; j < o.joints; ++j) {
                const float centre = (static_cast<float>(j) + 0.5f) * bone;
                weights[static_cast<std::size_t>(j)] = {std::max(0.0f, 1.0f - std::abs(y - centre) / (o.blend * bone)), j};
            }
            std::partial_sort(weights.begin(), weights.begin() + std::min(o.influences, o.joints), weights.end(),
                              [](const auto& p, const auto& q) { return p.first > q.first || (p.first == q.first && p.second < q.second); });
            std::array<float, 8> w{};
            std::array<std::uint16_t, 8> jt{};
            float sum = 0.0f;
            for (int k = 0; k < std::min(o.influences, o.joints); ++k) {
                w[static_cast<std::size_t>(k)] = weights[static_cast<std::size_t>(k)].first;
                jt[static_cast<std::size_t>(k)] = static_cast<std::uint16_t>(weights[static_cast<std::size_t>(k)].second);
                sum += w[static_cast<std::size_t>(k)];
            }
            if (sum <= 0.0f) w[0] = sum = 1.0f;  // beyond every tent (cannot happen with blend >= 0.5)
            for (float& x : w) x /= sum;
            for (int s = 0; s < ring; ++s) {
                const float angle = 2.0f * std::numbers::pi_v<float> * static_cast<float>(s) / static_cast<float>(o.segments);
                const glm::vec3 n(std::cos(angle), 0.0f, -std::sin(angle));  // counter-clockwise seen from outside
                mesh->positions.push_back(glm::vec3(o.radius * n.x, y, o.radius * n.z));
                mesh->normals.push_back(n);
                mesh->texcoords.emplace_back(static_cast<float>(s) / static_cast<float>(o.segments), 1.0f - t);
                mesh->joints0.emplace_back(jt[0], jt[1], jt[2], jt[3]);
                mesh->weights0.emplace_back(w[0], w[1], w[2], w[3]);
                if (o.influences == 8) {
                    mesh->joints1.emplace_back(jt[4], jt[5], jt[6], jt[7]);
                    mesh->weights1.emplace_back(w[4], w[5], w[6], w[7]);
                }
            }
        }
        for (int r = 0; r + 1 < o.ringsPerBand; ++r)
            for (int s = 0; s < o.segments; ++s) {
                const std::uint32_t a = base + static_cast<std::uint32_t>(r * ring + s), b1 = a + 1,
                                    c = a + static_cast<std::uint32_t>(ring) + 1, d = a + static_cast<std::uint32_t>(ring);
                for (std::uint32_t i : {a, b1, c, a, c, d}) mesh->indices.push_back(i);
            }
    }
    return mesh;
}

void bendTubePalette(const SkinnedTubeOptions& options, float anglePerJoint, std::vector<glm::mat4>& palette,
                     float twistPerJoint) {
    if (options.joints < 1) throw std::invalid_argument("bendTubePalette: options.joints must be positive");
    const float bone = options.height / static_cast<float>(options.joints);
    palette.resize(static_cast<std::size_t>(options.joints));
    glm::mat4 world(1.0f);  // joint 0, the root, stays in its bind pose
    for (int j = 0; j < options.joints; ++j) {
        if (j > 0) {
            world = glm::translate(world, glm::vec3(0.0f, bone, 0.0f));
            world = glm::rotate(world, anglePerJoint, glm::vec3(0.0f, 0.0f, 1.0f));
            world = glm::rotate(world, twistPerJoint, glm::vec3(0.0f, 1.0f, 0.0f));
        }
        const glm::mat4 inverseBind = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -bone * static_cast<float>(j), 0.0f));
        palette[static_cast<std::size_t>(j)] = world * inverseBind;
    }
}

}  // namespace throng
