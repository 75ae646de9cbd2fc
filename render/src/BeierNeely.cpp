#include "throng/render/BeierNeely.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

#include <glm/geometric.hpp>

namespace throng {
namespace {

glm::vec2 perpendicular(glm::vec2 d) { return {-d.y, d.x}; }

// One line's contribution at `x`: the source position it proposes and its weight. Written in the
// order of the GLSL in GpuMorpher (kMorphFragmentShader) so that both round alike. `attr` is the
// classic line (weight 1, radius 0, depth 0) when the caller gives no attributes: the extra factors
// are then exactly 1 and the capsule distance exactly the classic distance.
void lineContribution(glm::vec2 x, const FeatureLine& dst, const FeatureLine& src, const MorphParameters& m,
                      const LineAttributes& attr, glm::vec2& proposed, float& weight) {
    const glm::vec2 d = dst.q - dst.p;
    const float len2 = glm::dot(d, d);
    const float len = std::sqrt(len2);
    const glm::vec2 xp = x - dst.p;
    const glm::vec2 s = src.q - src.p;
    const float slen = std::sqrt(glm::dot(s, s));
    float dist;
    float along = 0.0f;  // where along the line the nearest point is (0 at p, 1 at q)
    if (len < kDegenerateFeatureLength || slen < kDegenerateFeatureLength) {
        // A point feature (or a line collapsing to one): its neighbourhood translates with it.
        proposed = src.p + xp;
        dist = std::sqrt(glm::dot(xp, xp));
    } else {
        const float u = glm::dot(xp, d) / len2;
        const float v = glm::dot(xp, perpendicular(d)) / len;
        proposed = src.p + u * s + v * (perpendicular(s) / slen);
        if (u < 0.0f) dist = std::sqrt(glm::dot(xp, xp));
        else if (u > 1.0f) {
            const glm::vec2 xq = x - dst.q;
            dist = std::sqrt(glm::dot(xq, xq));
            along = 1.0f;
        } else {
            dist = std::fabs(v);
            along = u;
        }
    }
    const float a = std::max(m.a, 1e-3f);
    const float lenP = std::pow(std::max(len, kMinFeatureLength), m.p);
    const float capsule = std::max(dist - attr.radius, 0.0f);
    // Depth decides only among the limbs whose flesh holds the pixel: elsewhere distance decides.
    float order = 1.0f;
    if (m.depth != 0.0f && capsule <= 0.0f) {
        const float z = attr.depthP + (attr.depthQ - attr.depthP) * along;
        order = std::exp(std::clamp(m.depth * z, -kMaxDepthExponent, kMaxDepthExponent));
    }
    weight = std::pow(lenP / (a + capsule), m.b) * (attr.weight * order);
}

float texel(const Image& image, int x, int y, int c) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return 0.0f;
    return static_cast<float>(image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4 + c]) / 255.0f;
}

void checkImage(const Image& image, const char* what) {
    if (!image.valid()) throw std::invalid_argument(std::string("morphImages: the ") + what + " image is invalid");
}

}  // namespace

glm::vec2 beierNeelySourcePosition(glm::vec2 x, std::span<const FeatureLine> destination,
                                   std::span<const FeatureLine> source, const MorphParameters& parameters,
                                   std::span<const LineAttributes> attributes) {
    glm::vec2 sum(0.0f);
    float weightSum = 0.0f;
    const std::size_t n = std::min(destination.size(), source.size());
    const LineAttributes classic;
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec2 proposed;
        float w;
        lineContribution(x, destination[i], source[i], parameters, i < attributes.size() ? attributes[i] : classic, proposed, w);
        sum += (proposed - x) * w;
        weightSum += w;
    }
    if (!(weightSum > 0.0f) || !std::isfinite(weightSum)) return x;
    const glm::vec2 result = x + sum / weightSum;
    return std::isfinite(result.x) && std::isfinite(result.y) ? result : x;
}

void interpolateLines(std::span<const FeatureLine> a, std::span<const FeatureLine> b, float t,
                      std::vector<FeatureLine>& out) {
    if (a.size() != b.size())
        throw std::invalid_argument("interpolateLines: " + std::to_string(a.size()) + " lines against " +
                                    std::to_string(b.size()));
    out.resize(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        out[i].p = a[i].p + (b[i].p - a[i].p) * t;
        out[i].q = a[i].q + (b[i].q - a[i].q) * t;
    }
}

void samplePremultiplied(const Image& image, glm::vec2 position, float rgba[4]) {
    const float fx = position.x - 0.5f, fy = position.y - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float wx = fx - x0f, wy = fy - y0f;
    // Far outside: transparent (also keeps the int conversion in range).
    if (!(std::fabs(x0f) < 1e6f && std::fabs(y0f) < 1e6f)) {
        rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.0f;
        return;
    }
    const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
    for (int c = 0; c < 4; ++c) {
        const float top = texel(image, x0, y0, c) * (1.0f - wx) + texel(image, x0 + 1, y0, c) * wx;
        const float bottom = texel(image, x0, y0 + 1, c) * (1.0f - wx) + texel(image, x0 + 1, y0 + 1, c) * wx;
        rgba[c] = top * (1.0f - wy) + bottom * wy;
    }
}

void checkLineAttributes(std::span<const LineAttributes> attributes, std::size_t lines, const char* who) {
    if (!attributes.empty() && attributes.size() != lines)
        throw std::invalid_argument(std::string(who) + ": " + std::to_string(attributes.size()) + " line attributes for " +
                                    std::to_string(lines) + " lines");
    for (std::size_t i = 0; i < attributes.size(); ++i) {
        const LineAttributes& a = attributes[i];
        if (!std::isfinite(a.weight) || !std::isfinite(a.radius) || !std::isfinite(a.depthP) || !std::isfinite(a.depthQ))
            throw std::invalid_argument(std::string(who) + ": line attribute " + std::to_string(i) + " is not finite");
        if (a.weight < 0.0f || a.radius < 0.0f)
            throw std::invalid_argument(std::string(who) + ": line attribute " + std::to_string(i) +
                                        " has a negative weight or radius");
    }
}

Image morphImages(const Image& from, std::span<const FeatureLine> fromLines, const Image& to,
                  std::span<const FeatureLine> toLines, std::span<const FeatureLine> targetLines, float t,
                  const MorphParameters& parameters, unsigned threads, std::span<const LineAttributes> attributes) {
    checkImage(from, "first");
    checkImage(to, "second");
    if (from.width != to.width || from.height != to.height)
        throw std::invalid_argument("morphImages: images of different sizes");
    if (fromLines.size() != targetLines.size() || toLines.size() != targetLines.size())
        throw std::invalid_argument("morphImages: the three line sets differ in size");
    if (!std::isfinite(t)) throw std::invalid_argument("morphImages: t is not finite");
    checkLineAttributes(attributes, targetLines.size(), "morphImages");
    if (!std::isfinite(parameters.depth)) throw std::invalid_argument("morphImages: the depth parameter is not finite");

    Image out;
    out.name = from.name + "~" + to.name;
    out.width = from.width;
    out.height = from.height;
    out.rgba.assign(from.rgba.size(), 0);
    const auto rows = [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < out.width; ++x) {
                const glm::vec2 p(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
                float c0[4], c1[4];
                samplePremultiplied(from, beierNeelySourcePosition(p, targetLines, fromLines, parameters, attributes), c0);
                samplePremultiplied(to, beierNeelySourcePosition(p, targetLines, toLines, parameters, attributes), c1);
                std::uint8_t* o = &out.rgba[(static_cast<std::size_t>(y) * out.width + x) * 4];
                for (int c = 0; c < 4; ++c) {
                    const float v = c0[c] * (1.0f - t) + c1[c] * t;
                    o[c] = static_cast<std::uint8_t>(std::floor(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f));
                }
            }
    };
    threads = std::clamp(threads, 1u, static_cast<unsigned>(out.height));
    if (threads == 1) {
        rows(0, out.height);
    } else {
        std::vector<std::thread> pool;
        for (unsigned i = 0; i < threads; ++i)
            pool.emplace_back(rows, static_cast<int>(out.height * i / threads), static_cast<int>(out.height * (i + 1) / threads));
        for (auto& th : pool) th.join();
    }
    return out;
}

}  // namespace throng
