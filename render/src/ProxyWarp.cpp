#include "throng/render/ProxyWarp.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "throng/render/BeierNeely.h"

namespace throng {
namespace {

constexpr float kEmpty = -std::numeric_limits<float>::infinity();

// Calls `pixel(x, y, b0, b1, b2)` for every pixel centre inside the projected triangle (either
// winding), with its barycentric coordinates.
template <class F>
void rasterise(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, int size, F&& pixel) {
    const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (!(std::fabs(area) > 1e-12f)) return;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}) - 0.5f)));
    const int x1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}) - 0.5f)));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}) - 0.5f)));
    const int y1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}) - 0.5f)));
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
            const float w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
            const float w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
            const float w2 = 1.0f - w0 - w1;
            if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) continue;
            pixel(x, y, w0, w1, w2);
        }
}

// Catmull-Rom sample of premultiplied `image` at `position` (pixels, centres at +0.5), transparent
// outside, clamped to [0, 1].
void sampleBicubic(const Image& image, glm::vec2 position, float rgba[4]) {
    const float fx = position.x - 0.5f, fy = position.y - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    if (!(std::fabs(x0f) < 1e6f && std::fabs(y0f) < 1e6f)) {
        rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.0f;
        return;
    }
    const float tx = fx - x0f, ty = fy - y0f;
    const auto weights = [](float t, float w[4]) {
        const float t2 = t * t, t3 = t2 * t;
        w[0] = 0.5f * (-t3 + 2.0f * t2 - t);
        w[1] = 0.5f * (3.0f * t3 - 5.0f * t2 + 2.0f);
        w[2] = 0.5f * (-3.0f * t3 + 4.0f * t2 + t);
        w[3] = 0.5f * (t3 - t2);
    };
    float wx[4], wy[4];
    weights(tx, wx);
    weights(ty, wy);
    const int x0 = static_cast<int>(x0f) - 1, y0 = static_cast<int>(y0f) - 1;
    for (int c = 0; c < 4; ++c) rgba[c] = 0.0f;
    for (int j = 0; j < 4; ++j) {
        const int y = y0 + j;
        if (y < 0 || y >= image.height) continue;
        for (int i = 0; i < 4; ++i) {
            const int x = x0 + i;
            if (x < 0 || x >= image.width) continue;
            const std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4];
            const float w = wx[i] * wy[j] / 255.0f;
            for (int c = 0; c < 4; ++c) rgba[c] += w * static_cast<float>(p[c]);
        }
    }
    rgba[3] = std::clamp(rgba[3], 0.0f, 1.0f);
    for (int c = 0; c < 3; ++c) rgba[c] = std::clamp(rgba[c], 0.0f, rgba[3]);  // premultiplied: colour <= alpha
}

// Depth buffer (largest depth toward the eye wins) of the projected proxy.
std::vector<float> depthBuffer(const ProxyMesh& mesh, const std::vector<glm::vec3>& p) {
    const int s = mesh.cellSize();
    std::vector<float> z(static_cast<std::size_t>(s) * s, kEmpty);
    for (const auto& t : mesh.triangles())
        rasterise(p[t[0]], p[t[1]], p[t[2]], s, [&](int x, int y, float w0, float w1, float w2) {
            float& d = z[static_cast<std::size_t>(y) * s + x];
            d = std::max(d, w0 * p[t[0]].z + w1 * p[t[1]].z + w2 * p[t[2]].z);
        });
    return z;
}

}  // namespace

float checkProxyWarp(const ProxyMesh& mesh, std::span<const ProxySource> sources, double keyframe, const ProxyWarpOptions& options,
                     const char* who) {
    const int s = mesh.cellSize();
    const std::string w(who);
    if (sources.empty()) throw std::invalid_argument(w + ": no source");
    float weightSum = 0.0f;
    for (std::size_t i = 0; i < sources.size(); ++i) {
        const ProxySource& src = sources[i];
        if (!src.image || !src.image->valid() || src.image->width != s || src.image->height != s)
            throw std::invalid_argument(w + ": source " + std::to_string(i) + " is missing or not " + std::to_string(s) + " pixels square");
        if (src.keyframe < 0 || src.keyframe >= mesh.keyframeCount())
            throw std::invalid_argument(w + ": source " + std::to_string(i) + " key-frame out of range");
        if (!(src.weight >= 0.0f) || !std::isfinite(src.weight))
            throw std::invalid_argument(w + ": source " + std::to_string(i) + " has a negative or non-finite weight");
        weightSum += src.weight;
    }
    if (!(weightSum > 0.0f)) throw std::invalid_argument(w + ": the source weights sum to zero");
    if (!std::isfinite(keyframe)) throw std::invalid_argument(w + ": the target key-frame is not finite");
    if (!(options.depthTolerance >= 0.0f) || !(options.distrust >= 0.0f && options.distrust <= 1.0f) || options.rim < 0)
        throw std::invalid_argument(w + ": depth tolerance and rim must be >= 0, distrust in [0, 1]");
    return weightSum;
}

Image warpProxy(const ProxyMesh& mesh, std::span<const ProxySource> sources, const glm::vec3& toEye, double keyframe,
                const ProxyWarpOptions& options) {
    const int s = mesh.cellSize();
    const float weightSum = checkProxyWarp(mesh, sources, keyframe, options, "warpProxy");

    const std::size_t pixels = static_cast<std::size_t>(s) * s, n = sources.size();
    const std::vector<glm::vec3> target = mesh.project(keyframe, toEye);
    std::vector<std::vector<glm::vec3>> projected(n), normals(n);
    std::vector<std::vector<float>> depth(n);
    const bool useNormals = options.normalSharpness > 0.0f;
    for (std::size_t i = 0; i < n; ++i) {
        projected[i] = mesh.project(sources[i].keyframe, sources[i].toEye);
        depth[i] = depthBuffer(mesh, projected[i]);
        if (useNormals) normals[i] = mesh.normals(sources[i].keyframe);
    }
    const std::vector<glm::vec3> targetNormals = useNormals ? mesh.normals(keyframe) : std::vector<glm::vec3>{};
    // Per pixel and source: how alike the surface faces in the source and in the target (1 when
    // normals are not used).
    std::vector<float> facing(useNormals ? pixels * n : 0, 1.0f);
    // The target raster: per pixel the nearest triangle's point, as (x, y, depth) in every source.
    std::vector<float> zTarget(pixels, kEmpty);
    std::vector<glm::vec3> fetch(pixels * n);
    for (const auto& t : mesh.triangles())
        rasterise(target[t[0]], target[t[1]], target[t[2]], s, [&](int x, int y, float w0, float w1, float w2) {
            const std::size_t i = static_cast<std::size_t>(y) * s + x;
            const float z = w0 * target[t[0]].z + w1 * target[t[1]].z + w2 * target[t[2]].z;
            if (z <= zTarget[i]) return;
            zTarget[i] = z;
            for (std::size_t k = 0; k < n; ++k)
                fetch[i * n + k] = w0 * projected[k][t[0]] + w1 * projected[k][t[1]] + w2 * projected[k][t[2]];
            if (!useNormals) return;
            const glm::vec3 nt = w0 * targetNormals[t[0]] + w1 * targetNormals[t[1]] + w2 * targetNormals[t[2]];
            for (std::size_t k = 0; k < n; ++k) {
                const glm::vec3 ns = w0 * normals[k][t[0]] + w1 * normals[k][t[1]] + w2 * normals[k][t[2]];
                const float lens = glm::length(ns) * glm::length(nt);
                const float c = lens > 0.0f ? glm::dot(ns, nt) / lens : 1.0f;
                facing[i * n + k] = std::pow(0.5f * (1.0f + std::clamp(c, -1.0f, 1.0f)), options.normalSharpness);
            }
        });
    // The rim: uncovered pixels near the outline take the nearest covered pixel's flow (translated),
    // grown one pixel ring at a time.
    std::vector<int> from(pixels, -1);
    for (std::size_t i = 0; i < pixels; ++i)
        if (zTarget[i] != kEmpty) from[i] = static_cast<int>(i);
    for (int ring = 0; ring < options.rim; ++ring) {
        std::vector<int> next = from;
        for (int y = 0; y < s; ++y)
            for (int x = 0; x < s; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * s + x;
                if (from[i] >= 0) continue;
                float best = std::numeric_limits<float>::infinity();
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if (nx < 0 || ny < 0 || nx >= s || ny >= s) continue;
                        const int f = from[static_cast<std::size_t>(ny) * s + nx];
                        if (f < 0) continue;
                        const float fx = static_cast<float>(f % s) - static_cast<float>(x), fy = static_cast<float>(f / s) - static_cast<float>(y);
                        const float d = fx * fx + fy * fy;
                        if (d < best) best = d, next[i] = f;
                    }
            }
        from = std::move(next);
    }

    Image out;
    out.name = "proxy warp";
    out.width = out.height = s;
    out.rgba.assign(pixels * 4, 0);
    std::vector<float> w(n);
    for (std::size_t i = 0; i < pixels; ++i) {
        if (from[i] < 0) continue;
        const auto f = static_cast<std::size_t>(from[i]);
        const glm::vec2 shift(static_cast<float>(static_cast<int>(i % s) - static_cast<int>(f % s)),
                              static_cast<float>(static_cast<int>(i / s) - static_cast<int>(f / s)));
        float sum = 0.0f;
        for (std::size_t k = 0; k < n; ++k) {
            const glm::vec3& q = fetch[f * n + k];
            const int qx = static_cast<int>(std::floor(q.x)), qy = static_cast<int>(std::floor(q.y));
            bool visible = true;
            if (qx >= 0 && qy >= 0 && qx < s && qy < s) {
                const float front = depth[k][static_cast<std::size_t>(qy) * s + qx];
                visible = front == kEmpty || q.z >= front - options.depthTolerance;
            }
            w[k] = sources[k].weight * (visible ? 1.0f : options.distrust) * (useNormals ? facing[f * n + k] : 1.0f);
            sum += w[k];
        }
        if (!(sum > 0.0f)) {
            sum = weightSum;
            for (std::size_t k = 0; k < n; ++k) w[k] = sources[k].weight;
        }
        float c[4] = {0, 0, 0, 0};
        for (std::size_t k = 0; k < n; ++k) {
            if (w[k] <= 0.0f) continue;
            const glm::vec3& q = fetch[f * n + k];
            float sample[4];
            if (options.bicubic) sampleBicubic(*sources[k].image, glm::vec2(q.x, q.y) + shift, sample);
            else samplePremultiplied(*sources[k].image, glm::vec2(q.x, q.y) + shift, sample);
            for (int ch = 0; ch < 4; ++ch) c[ch] += sample[ch] * w[k] / sum;
        }
        // Covered pixels: the blend of premultiplied samples divided by its alpha is the colour of
        // the opaque texels only, each source counted by how much of its sample is the figure.
        if (options.opaqueInside && zTarget[i] != kEmpty && c[3] > 1e-3f) {
            for (int ch = 0; ch < 3; ++ch) c[ch] /= c[3];
            c[3] = 1.0f;
        }
        for (int ch = 0; ch < 4; ++ch)
            out.rgba[i * 4 + ch] = static_cast<std::uint8_t>(std::floor(std::clamp(c[ch], 0.0f, 1.0f) * 255.0f + 0.5f));
    }
    return out;
}

}  // namespace throng
