#include "throng/render/MorphFeatures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "throng/render/ImpostorAtlas.h"

namespace throng {

std::vector<float> boneWeights(const FeatureTrack& track, int before, int after, const FeatureOptions& options) {
    const std::size_t n = track.boneCount();
    std::vector<float> w(n, 1.0f);
    if (options.weighting == LineWeighting::Uniform || n == 0) return w;
    std::vector<float> value(n);
    if (options.weighting == LineWeighting::Length)
        for (std::size_t i = 0; i < n; ++i) value[i] = glm::length(track.childJoint(before, i) - track.parentJoint(before, i));
    else
        value = track.motion(before, after);
    double mean = 0;
    for (float v : value) mean += v;
    mean /= static_cast<double>(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double relative = mean > 0 ? value[i] / mean : 1.0;
        const double base = options.weighting == LineWeighting::Motion ? relative + 0.1 : relative;
        // A bone of zero length still weighs a little: its point feature must not vanish.
        w[i] = static_cast<float>(std::pow(std::max(base, 1e-3), static_cast<double>(options.weightExponent)));
    }
    return w;
}

void viewFeatures(const FeatureTrack& track, int keyframe, const glm::vec3& toEye, std::span<const std::uint32_t> bones,
                  std::span<const float> weights, const FeatureOptions& options, std::vector<FeatureLine>& lines,
                  std::vector<LineAttributes>& attributes) {
    if (weights.size() != track.boneCount())
        throw std::invalid_argument("viewFeatures: " + std::to_string(weights.size()) + " weights for " +
                                    std::to_string(track.boneCount()) + " bones");
    const std::vector<FeatureLine> all = track.lines(keyframe, toEye);
    const std::vector<LineAttributes> allAttributes = track.attributes(keyframe, toEye);
    lines.clear();
    attributes.clear();
    for (std::uint32_t b : bones) {
        if (b >= all.size()) throw std::invalid_argument("viewFeatures: bone " + std::to_string(b) + " out of range");
        const FeatureLine& l = all[b];
        LineAttributes a = allAttributes[b];
        a.weight = weights[b];
        const float radius = a.radius * options.radiusScale;
        a.radius = options.capsules ? radius : 0.0f;
        lines.push_back(l);
        attributes.push_back(a);
        const auto point = [&](glm::vec2 p, float depth) {
            lines.push_back({p, p});
            LineAttributes pa = a;
            pa.radius = 0.0f;
            pa.depthP = pa.depthQ = depth;
            attributes.push_back(pa);
        };
        switch (options.extra) {
            case ExtraFeatures::None: break;
            case ExtraFeatures::JointPoints:
                point(l.p, a.depthP);
                point(l.q, a.depthQ);
                [[fallthrough]];
            case ExtraFeatures::Midpoints: point(0.5f * (l.p + l.q), 0.5f * (a.depthP + a.depthQ)); break;
            case ExtraFeatures::Silhouettes: {
                const glm::vec2 d = l.q - l.p;
                const float len = glm::length(d);
                // A bone seen end-on has no outline direction: its outline lines sit on the axis.
                const glm::vec2 side = len > kDegenerateFeatureLength ? glm::vec2(-d.y, d.x) / len * radius : glm::vec2(0.0f);
                for (float sign : {-1.0f, 1.0f}) {
                    lines.push_back({l.p + sign * side, l.q + sign * side});
                    LineAttributes sa = a;
                    sa.radius = 0.0f;
                    attributes.push_back(sa);
                }
                break;
            }
        }
    }
    // Depths above the farthest feature, so depth order only ever raises a weight.
    float lowest = 0.0f;
    for (std::size_t i = 0; i < attributes.size(); ++i)
        lowest = i == 0 ? std::min(attributes[i].depthP, attributes[i].depthQ) : std::min({lowest, attributes[i].depthP, attributes[i].depthQ});
    for (LineAttributes& a : attributes) a.depthP -= lowest, a.depthQ -= lowest;
}

CellFeatures droppedCellFeatures(const ImpostorAtlas& atlas, const FeatureTrack& track, std::uint32_t view, int keyframe,
                                 const FeatureOptions& options) {
    if (track.boneCount() != atlas.boneCount() || track.keyframeCount() != atlas.keyframeCount())
        throw std::invalid_argument("droppedCellFeatures: the track (" + std::to_string(track.boneCount()) + " bones, " +
                                    std::to_string(track.keyframeCount()) + " key-frames) does not match the atlas (" +
                                    std::to_string(atlas.boneCount()) + ", " + std::to_string(atlas.keyframeCount()) + ")");
    if (view >= atlas.views().viewCount()) throw std::invalid_argument("droppedCellFeatures: view " + std::to_string(view) + " out of range");
    if (keyframe < 0 || keyframe >= atlas.keyframeCount())
        throw std::invalid_argument("droppedCellFeatures: key-frame " + std::to_string(keyframe) + " out of range");
    int before = 0, after = 0;
    float t = 0.5f;
    atlas.neighbours(keyframe, before, after, t);
    const std::vector<std::uint32_t> bones = atlas.strongestBones(options.bones);
    const std::vector<float> weights = boneWeights(track, before, after, options);
    const glm::vec3 eye = atlas.views().direction(view);
    CellFeatures f;
    viewFeatures(track, before, eye, bones, weights, options, f.from, f.fromAttributes);
    viewFeatures(track, after, eye, bones, weights, options, f.to, f.toAttributes);
    viewFeatures(track, keyframe, eye, bones, weights, options, f.target, f.targetAttributes);
    const std::size_t perBone = options.extra == ExtraFeatures::None ? 1
                                : options.extra == ExtraFeatures::Midpoints ? 2
                                : options.extra == ExtraFeatures::JointPoints ? 4
                                                                              : 3;
    for (std::uint32_t b : bones)
        for (std::size_t k = 0; k < perBone; ++k) {
            f.bones.push_back(b);
            f.primary.push_back(k == 0 ? 1 : 0);
        }
    return f;
}

}  // namespace throng
