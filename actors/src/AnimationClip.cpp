#include "throng/actors/AnimationClip.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>

#include "throng/actors/ActorTemplate.h"

namespace throng {
namespace {

std::string channelName(const std::string& clip, std::size_t i) {
    return "clip '" + clip + "', channel " + std::to_string(i);
}

// Shortest-arc spherical interpolation, robust when q0 ~ q1 and when q0 ~ -q1.
glm::quat slerpShortest(glm::quat a, glm::quat b, float u, OpTally* ops) {
    float cosTheta = glm::dot(a, b);
    THRONG_TALLY(ops, 4, 4, 0, 0);
    if (cosTheta < 0.0f) {  // q and -q are the same rotation: take the short way round
        b = -b;
        cosTheta = -cosTheta;
    }
    if (cosTheta > 0.9995f) {  // nearly equal: linear blend, renormalized, avoids dividing by sin ~ 0
        const glm::quat q = glm::normalize(a * (1.0f - u) + b * u);
        THRONG_TALLY(ops, 12, 8, 4, 1);
        return q;
    }
    const float theta = std::acos(cosTheta);
    const float sinTheta = std::sin(theta);
    const float wa = std::sin((1.0f - u) * theta) / sinTheta;
    const float wb = std::sin(u * theta) / sinTheta;
    THRONG_TALLY(ops, 10, 5, 2, 4);  // transcendental functions counted as square roots
    return a * wa + b * wb;
}

}  // namespace

AnimationClip::AnimationClip(std::string name, std::vector<ClipChannel> channels)
    : name_(std::move(name)), channels_(std::move(channels)) {
    for (std::size_t i = 0; i < channels_.size(); ++i) {
        const ClipChannel& c = channels_[i];
        if (c.times.empty()) throw std::invalid_argument(channelName(name_, i) + ": has no keys");
        for (std::size_t k = 0; k < c.times.size(); ++k) {
            if (!std::isfinite(c.times[k]) || c.times[k] < 0.0f)
                throw std::invalid_argument(channelName(name_, i) + ": key " + std::to_string(k) +
                                            " has an invalid time (" + std::to_string(c.times[k]) + ")");
            if (k > 0 && !(c.times[k] > c.times[k - 1]))
                throw std::invalid_argument(channelName(name_, i) + ": key times are not strictly increasing at key " +
                                            std::to_string(k));
        }
        const std::size_t perKey = c.values.size() / c.times.size();
        if (perKey == 0 || perKey * c.times.size() != c.values.size())
            throw std::invalid_argument(channelName(name_, i) + ": " + std::to_string(c.values.size()) +
                                        " values do not divide into " + std::to_string(c.times.size()) + " keys");
        for (float v : c.values)
            if (!std::isfinite(v)) throw std::invalid_argument(channelName(name_, i) + ": has a non-finite value");
        duration_ = std::max(duration_, static_cast<double>(c.times.back()));
    }
}

double AnimationClip::localTime(double t, bool loop) const {
    if (!(duration_ > 0.0)) return 0.0;
    if (loop) {
        double u = std::fmod(t, duration_);  // exact in double, even at t = 10^6 s
        if (u < 0.0) u += duration_;
        return u;
    }
    return std::clamp(t, 0.0, duration_);
}

void AnimationClip::sampleChannel(const ClipChannel& c, int width, bool orientation, float ft, float* out,
                                  OpTally* ops, bool holdKeys) {
    const std::size_t stride = valuesPerKey(c.interpolation, width);
    const std::size_t keys = c.times.size();
    // Key k with times[k] <= t < times[k+1], found by binary search.
    const auto it = std::upper_bound(c.times.begin(), c.times.end(), ft);
    const std::size_t upper = static_cast<std::size_t>(it - c.times.begin());
    THRONG_TALLY(ops, 0, static_cast<std::uint64_t>(std::bit_width(keys)), 0, 0);
    const std::size_t valueIndex = c.interpolation == Interpolation::CubicSpline ? 1 : 0;  // skip in-tangent
    if (upper == 0 || upper == keys || c.interpolation == Interpolation::Step || holdKeys) {
        const std::size_t k = upper == 0 ? 0 : upper - 1;
        std::copy_n(c.values.data() + k * stride + valueIndex * static_cast<std::size_t>(width), width, out);
        return;
    }
    const std::size_t k0 = upper - 1, k1 = upper;
    const float t0 = c.times[k0], t1 = c.times[k1];
    const float dt = t1 - t0;
    const float u = (ft - t0) / dt;
    THRONG_TALLY(ops, 0, 2, 1, 0);
    const float* v0 = c.values.data() + k0 * stride;
    const float* v1 = c.values.data() + k1 * stride;
    if (c.interpolation == Interpolation::Linear) {
        if (orientation) {
            const glm::quat q = slerpShortest(glm::quat(v0[3], v0[0], v0[1], v0[2]),
                                              glm::quat(v1[3], v1[0], v1[1], v1[2]), u, ops);
            out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
        } else {
            for (int j = 0; j < width; ++j) out[j] = v0[j] + (v1[j] - v0[j]) * u;
            THRONG_TALLY(ops, static_cast<std::uint64_t>(width), 2u * width, 0, 0);
        }
        return;
    }
    // Hermite basis with tangents scaled by the key interval (glTF appendix C).
    const float u2 = u * u, u3 = u2 * u;
    const float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    const float* p0 = v0 + width;       // value of k0
    const float* m0 = v0 + 2 * width;   // out-tangent of k0
    const float* p1 = v1 + width;       // value of k1
    const float* m1 = v1;               // in-tangent of k1
    for (int j = 0; j < width; ++j) out[j] = h00 * p0[j] + h10 * dt * m0[j] + h01 * p1[j] + h11 * dt * m1[j];
    THRONG_TALLY(ops, 10 + 6u * width, 8 + 3u * width, 0, 0);
    if (orientation) {
        const float n = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
        if (n > 0.0f)
            for (int j = 0; j < 4; ++j) out[j] /= n;
        THRONG_TALLY(ops, 4, 3, 4, 1);
    }
}

std::size_t AnimationClip::sample(const ActorTemplate& tmpl, double t, bool loop, std::span<const std::uint8_t> active,
                                  std::span<float> dofs, OpTally* ops, bool holdKeys) const {
    const float ft = static_cast<float>(localTime(t, loop));
    std::size_t written = 0;
    for (const ClipChannel& c : channels_) {
        if (c.target != ClipChannel::Target::NodeDof) continue;
        if (!active.empty() && !active[c.node]) continue;  // inactive nodes are never evaluated
        const DofKind kind = tmpl.nodes()[c.node].dofs[c.dof].kind;
        const int width = dofValueCount(kind);
        sampleChannel(c, width, kind == DofKind::Orientation, ft, dofs.data() + tmpl.dofValueOffset(c.node, c.dof), ops,
                      holdKeys);
        written += static_cast<std::size_t>(width);
    }
    return written;
}

RootPose AnimationClip::sampleRoot(double t, bool loop, OpTally* ops, bool holdKeys) const {
    const float ft = static_cast<float>(localTime(t, loop));
    RootPose root;
    for (const ClipChannel& c : channels_) {
        if (c.target == ClipChannel::Target::RootTranslation) {
            sampleChannel(c, 3, false, ft, &root.translation.x, ops, holdKeys);
        } else if (c.target == ClipChannel::Target::RootOrientation) {
            float q[4];
            sampleChannel(c, 4, true, ft, q, ops, holdKeys);
            root.orientation = glm::normalize(glm::quat(q[3], q[0], q[1], q[2]));
        }
    }
    return root;
}

}  // namespace throng
