#include "throng/render/LimbMorph.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>

namespace throng {

int frontFeature(glm::vec2 x, std::span<const FeatureLine> lines, std::span<const LineAttributes> attributes,
                 std::span<const std::uint8_t> primary, float reach) {
    int best = -1;
    float bestDepth = 0.0f;
    const std::size_t n = std::min({lines.size(), attributes.size(), primary.size()});
    for (std::size_t i = 0; i < n; ++i) {
        const LineAttributes& a = attributes[i];
        if (!primary[i] || !(a.radius > 0.0f)) continue;
        const glm::vec2 d = lines[i].q - lines[i].p;
        const float len2 = glm::dot(d, d);
        const float u = len2 > 0.0f ? std::clamp(glm::dot(x - lines[i].p, d) / len2, 0.0f, 1.0f) : 0.0f;
        const glm::vec2 nearest = lines[i].p + u * d;
        if (glm::length(x - nearest) > a.radius * reach) continue;
        const float depth = a.depthP + (a.depthQ - a.depthP) * u;
        if (best < 0 || depth > bestDepth) best = static_cast<int>(i), bestDepth = depth;
    }
    return best;
}

Image morphLimbs(const Image& from, const Image& to, const CellFeatures& f, const FeatureTrack& track, float t,
                 const MorphParameters& parameters, const VisibilityOptions& visibility, unsigned threads) {
    if (!from.valid() || !to.valid()) throw std::invalid_argument("morphLimbs: an image is invalid");
    if (from.width != to.width || from.height != to.height) throw std::invalid_argument("morphLimbs: images of different sizes");
    const std::size_t n = f.target.size();
    if (f.from.size() != n || f.to.size() != n || f.fromAttributes.size() != n || f.toAttributes.size() != n ||
        f.targetAttributes.size() != n || f.bones.size() != n || f.primary.size() != n)
        throw std::invalid_argument("morphLimbs: the feature arrays differ in size");
    for (std::uint32_t b : f.bones)
        if (b >= track.boneCount()) throw std::invalid_argument("morphLimbs: bone " + std::to_string(b) + " is not in the track");
    checkLineAttributes(f.fromAttributes, n, "morphLimbs");
    checkLineAttributes(f.toAttributes, n, "morphLimbs");
    checkLineAttributes(f.targetAttributes, n, "morphLimbs");
    if (!std::isfinite(t) || !std::isfinite(parameters.depth)) throw std::invalid_argument("morphLimbs: t or the depth parameter is not finite");
    if (!(visibility.distrust >= 0.0f && visibility.distrust <= 1.0f) || !(visibility.reach > 0.0f) || !std::isfinite(visibility.reach))
        throw std::invalid_argument("morphLimbs: distrust must be in [0, 1] and reach positive");

    Image out;
    out.name = from.name + "~" + to.name;
    out.width = from.width;
    out.height = from.height;
    out.rgba.assign(from.rgba.size(), 0);
    const auto consistent = [&](int target, int source) {
        return target < 0 || source < 0 || track.related(f.bones[static_cast<std::size_t>(target)], f.bones[static_cast<std::size_t>(source)]);
    };
    const auto rows = [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < out.width; ++x) {
                const glm::vec2 p(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
                const glm::vec2 s0 = beierNeelySourcePosition(p, f.target, f.from, parameters, f.targetAttributes);
                const glm::vec2 s1 = beierNeelySourcePosition(p, f.target, f.to, parameters, f.targetAttributes);
                float c0[4], c1[4];
                samplePremultiplied(from, s0, c0);
                samplePremultiplied(to, s1, c1);
                const int front = frontFeature(p, f.target, f.targetAttributes, f.primary, visibility.reach);
                float w0 = 1.0f - t, w1 = t;
                if (front >= 0) {
                    if (!consistent(front, frontFeature(s0, f.from, f.fromAttributes, f.primary, visibility.reach))) w0 *= visibility.distrust;
                    if (!consistent(front, frontFeature(s1, f.to, f.toAttributes, f.primary, visibility.reach))) w1 *= visibility.distrust;
                }
                const float sum = w0 + w1;
                if (sum > 0.0f) w0 /= sum, w1 /= sum;
                else w0 = 1.0f - t, w1 = t;
                std::uint8_t* o = &out.rgba[(static_cast<std::size_t>(y) * out.width + x) * 4];
                for (int c = 0; c < 4; ++c) {
                    const float v = c0[c] * w0 + c1[c] * w1;
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
