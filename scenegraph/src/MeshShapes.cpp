#include "throng/scenegraph/MeshShapes.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace throng {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

void checkTessellation(const std::string& name, int segments, int minSegments, int rings, int minRings) {
    if (segments < minSegments || rings < minRings)
        throw std::invalid_argument("mesh '" + name + "': tessellation " + std::to_string(segments) + " x " +
                                    std::to_string(rings) + " is too coarse");
}

// Grid of (rings + 1) x (segments + 1) vertices given by `at(u, v)` (u around, v along), with
// normals from `normal(u, v)`, stitched into triangles.
template <class Position, class Normal>
void addGrid(MeshData& m, int segments, int rings, Position at, Normal normal) {
    const auto first = static_cast<std::uint32_t>(m.positions.size());
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const float u = float(s) / float(segments), v = float(r) / float(rings);
            m.positions.push_back(at(u, v));
            m.normals.push_back(normal(u, v));
            m.texcoords.emplace_back(u, v);
        }
    const auto row = static_cast<std::uint32_t>(segments + 1);
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const std::uint32_t a = first + static_cast<std::uint32_t>(r) * row + static_cast<std::uint32_t>(s);
            const std::uint32_t b = a + row;
            m.indices.insert(m.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
}

}  // namespace

std::shared_ptr<MeshData> makeBox(std::string name, const glm::vec3& c, const glm::vec3& h, const glm::vec4& color) {
    if (!(h.x > 0 && h.y > 0 && h.z > 0)) throw std::invalid_argument("mesh '" + name + "': box half extents must be positive");
    auto m = std::make_shared<MeshData>();
    m->name = std::move(name);
    m->baseColor = color;
    struct Face {
        glm::vec3 n, u, v;  // u x v = n: corners in u, v order are counter-clockwise from outside
    };
    const Face faces[6] = {{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                           {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
                           {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}};
    const glm::vec2 corner[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const Face& f : faces) {
        const auto base = static_cast<std::uint32_t>(m->positions.size());
        for (const glm::vec2& k : corner) {
            m->positions.push_back(c + (f.n + k.x * f.u + k.y * f.v) * h);
            m->normals.push_back(f.n);
            // The image's top row at the top of each side face.
            m->texcoords.emplace_back(0.5f * (k.x + 1.0f), 0.5f * (1.0f - k.y));
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m->indices.push_back(base + i);
    }
    return m;
}

std::shared_ptr<MeshData> makeCapsule(std::string name, const glm::vec3& base, float radius, float length, int segments,
                                      int rings, const glm::vec4& color) {
    checkTessellation(name, segments, 3, rings, 1);
    if (!(radius > 0.0f) || !(length >= 0.0f)) throw std::invalid_argument("mesh '" + name + "': capsule size must be positive");
    auto m = std::make_shared<MeshData>();
    m->name = std::move(name);
    m->baseColor = color;
    const int total = 2 * rings + 1;  // bottom cap, the cylinder, top cap
    auto angleAt = [&](float v, float& y, float& ring) {
        const float k = v * float(total);
        if (k <= float(rings)) {  // bottom cap
            const float a = -0.5f * kPi + 0.5f * kPi * k / float(rings);
            y = radius + radius * std::sin(a);
            ring = std::cos(a);
        } else if (k >= float(rings + 1)) {  // top cap
            const float a = 0.5f * kPi * (k - float(rings + 1)) / float(rings);
            y = radius + length + radius * std::sin(a);
            ring = std::cos(a);
        } else {
            y = radius + length * (k - float(rings));
            ring = 1.0f;
        }
    };
    addGrid(*m, segments, total,
            [&](float u, float v) {
                float y, ring;
                angleAt(v, y, ring);
                const float t = 2.0f * kPi * u;
                return base + glm::vec3(radius * ring * std::cos(t), y, -radius * ring * std::sin(t));
            },
            [&](float u, float v) {
                float y, ring;
                angleAt(v, y, ring);
                const float t = 2.0f * kPi * u;
                const float k = v * float(total);
                const float ny = k <= float(rings) ? -std::sqrt(std::max(0.0f, 1 - ring * ring))
                                 : k >= float(rings + 1) ? std::sqrt(std::max(0.0f, 1 - ring * ring)) : 0.0f;
                return glm::vec3(ring * std::cos(t), ny, -ring * std::sin(t));
            });
    return m;
}

std::shared_ptr<MeshData> makeSphere(std::string name, const glm::vec3& center, float radius, int segments, int rings,
                                     const glm::vec4& color) {
    checkTessellation(name, segments, 3, rings, 2);
    if (!(radius > 0.0f)) throw std::invalid_argument("mesh '" + name + "': sphere radius must be positive");
    auto m = std::make_shared<MeshData>();
    m->name = std::move(name);
    m->baseColor = color;
    auto dir = [](float u, float v) {
        const float theta = 2.0f * kPi * u, phi = kPi * v - 0.5f * kPi;
        return glm::vec3(std::cos(phi) * std::cos(theta), std::sin(phi), -std::cos(phi) * std::sin(theta));
    };
    addGrid(*m, segments, rings, [&](float u, float v) { return center + radius * dir(u, v); }, dir);
    return m;
}

std::shared_ptr<MeshData> mergeMeshes(std::string name, const MeshData& a, const MeshData& b) {
    auto m = std::make_shared<MeshData>(a);
    m->name = std::move(name);
    const auto offset = static_cast<std::uint32_t>(a.positions.size());
    m->positions.insert(m->positions.end(), b.positions.begin(), b.positions.end());
    if (!a.normals.empty() && !b.normals.empty()) m->normals.insert(m->normals.end(), b.normals.begin(), b.normals.end());
    else m->normals.clear();
    if (!a.texcoords.empty() && !b.texcoords.empty()) m->texcoords.insert(m->texcoords.end(), b.texcoords.begin(), b.texcoords.end());
    else m->texcoords.clear();
    for (std::uint32_t i : b.indices) m->indices.push_back(i + offset);
    m->joints0.clear(), m->weights0.clear(), m->joints1.clear(), m->weights1.clear();
    return m;
}

}  // namespace throng
