#pragma once
// Key-frame sampling (AnimationClip), written once over the scalar type: AnimationClip.cpp compiles
// it for float DOF values and double clip time, the FMULT tests for a counting type. Comparisons
// (those of the binary search among key times included) are counted as additions, sine, cosine
// and arc cosine are priced as square roots, and fmod as a division.

#include <algorithm>
#include <cstdint>
#include <span>

#include <glm/gtc/quaternion.hpp>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/AnimationClip.h"
#include "throng/actors/RootPose.h"
#include "throng/scenegraph/OpTally.h"
#include "throng/scenegraph/detail/ScalarMath.h"

namespace throng::detail {

/// Comparisons std::upper_bound makes among `keys` sorted values to return index `upper`: it
/// halves the range once per comparison, so replaying the halving on indices gives the count.
inline std::uint64_t upperBoundComparisons(std::size_t keys, std::size_t upper) {
    std::uint64_t compares = 0;
    std::size_t first = 0, len = keys;
    while (len > 0) {
        const std::size_t half = len >> 1, middle = first + half;
        ++compares;
        if (middle < upper) {  // the value is not below key `middle`: search above it
            first = middle + 1;
            len -= half + 1;
        } else {
            len = half;
        }
    }
    return compares;
}

/// `q` scaled to unit length, the identity when it is zero (glm::normalize's arithmetic, which
/// glm only compiles for built-in scalars): 8 mults, 4 adds, 1 div, 1 sqrt (4, 4, 0, 1 when zero).
template <class S>
glm::qua<S, glm::defaultp> normalizeQuat(const glm::qua<S, glm::defaultp>& q, OpTally* ops) {
    const S len = sqrtOf(glm::dot(q, q));
    THRONG_TALLY(ops, 4, 4, 0, 1);  // squared length, root, comparison
    if (len <= S(0)) return glm::qua<S, glm::defaultp>(S(1), S(0), S(0), S(0));
    const S oneOverLen = S(1) / len;
    THRONG_TALLY(ops, 4, 0, 1, 0);
    return glm::qua<S, glm::defaultp>(q.w * oneOverLen, q.x * oneOverLen, q.y * oneOverLen, q.z * oneOverLen);
}

/// Shortest-arc spherical interpolation, robust when a ~ b and when a ~ -b.
template <class S>
glm::qua<S, glm::defaultp> slerpShortest(glm::qua<S, glm::defaultp> a, glm::qua<S, glm::defaultp> b, S u, OpTally* ops) {
    S cosTheta = glm::dot(a, b);
    THRONG_TALLY(ops, 4, 5, 0, 0);  // dot product, two comparisons below (negations are free)
    if (cosTheta < S(0)) {  // q and -q are the same rotation: take the short way round
        b = -b;
        cosTheta = -cosTheta;
    }
    if (cosTheta > S(0.9995f)) {  // nearly equal: linear blend, renormalized, avoids dividing by sin ~ 0
        THRONG_TALLY(ops, 8, 5, 0, 0);
        return normalizeQuat(a * (S(1) - u) + b * u, ops);
    }
    const S theta = acosOf(cosTheta);
    const S sinTheta = sinOf(theta);
    const S wa = sinOf((S(1) - u) * theta) / sinTheta;
    const S wb = sinOf(u * theta) / sinTheta;
    THRONG_TALLY(ops, 10, 5, 2, 4);  // transcendental functions priced as square roots
    return a * wa + b * wb;
}

/// `t` wrapped into [0, duration) when `loop`, else clamped into [0, duration] (0 for an empty clip).
template <class W>
W clipLocalTime(W duration, W t, bool loop, OpTally* ops) {
    THRONG_TALLY(ops, 0, 1, 0, 0);
    if (!(duration > W(0))) return W(0);
    if (loop) {
        W u = fmodOf(t, duration);  // exact in double, even at t = 10^6 s
        THRONG_TALLY(ops, 0, 1, 1, 0);
        if (u < W(0)) {
            u += duration;
            THRONG_TALLY(ops, 0, 1, 0, 0);
        }
        return u;
    }
    THRONG_TALLY(ops, 0, 2, 0, 0);
    return std::clamp(t, W(0), duration);
}

/// The index of the first key of `times` after local time `t` (key k = result - 1 holds
/// times[k] <= t < times[k+1]), found by binary search.
template <class S>
std::size_t keyAfter(const std::vector<float>& times, S t, OpTally* ops) {
    const auto it = std::upper_bound(times.begin(), times.end(), t);
    const std::size_t upper = static_cast<std::size_t>(it - times.begin());
    THRONG_TALLY(ops, 0, upperBoundComparisons(times.size(), upper), 0, 0);
    return upper;
}

/// Writes channel `c`'s value at local time `t` into `out` (`width` values), its key found by
/// keyAfter (`upper`): channels sharing their key times share one search.
template <class S>
void sampleChannelAt(const ClipChannel& c, int width, bool orientation, S t, std::size_t upper, S* out, OpTally* ops,
                     bool holdKeys) {
    const std::size_t stride = valuesPerKey(c.interpolation, width);
    const std::size_t keys = c.times.size();
    const std::size_t valueIndex = c.interpolation == Interpolation::CubicSpline ? 1 : 0;  // skip in-tangent
    if (upper == 0 || upper == keys || c.interpolation == Interpolation::Step || holdKeys) {
        const std::size_t k = upper == 0 ? 0 : upper - 1;
        const float* held = c.values.data() + k * stride + valueIndex * static_cast<std::size_t>(width);
        switch (width) {  // the widths DOFs have, copied in registers (std::copy_n calls memmove)
            case 4: out[3] = held[3]; [[fallthrough]];
            case 3: out[2] = held[2]; out[1] = held[1]; [[fallthrough]];
            case 1: out[0] = held[0]; break;
            default: std::copy_n(held, width, out);
        }
        return;
    }
    const std::size_t k0 = upper - 1, k1 = upper;
    const S t0 = c.times[k0], t1 = c.times[k1];
    const S dt = t1 - t0;
    const S u = (t - t0) / dt;
    THRONG_TALLY(ops, 0, 2, 1, 0);
    const float* v0 = c.values.data() + k0 * stride;
    const float* v1 = c.values.data() + k1 * stride;
    if (c.interpolation == Interpolation::Linear) {
        if (orientation) {
            using Q = glm::qua<S, glm::defaultp>;
            const Q q = slerpShortest(Q(v0[3], v0[0], v0[1], v0[2]), Q(v1[3], v1[0], v1[1], v1[2]), u, ops);
            out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
        } else {
            for (int j = 0; j < width; ++j) {
                const S a = v0[j], b = v1[j];
                out[j] = a + (b - a) * u;
            }
            THRONG_TALLY(ops, static_cast<std::uint64_t>(width), 2u * width, 0, 0);
        }
        return;
    }
    // Hermite basis with tangents scaled by the key interval (glTF appendix C).
    const S u2 = u * u, u3 = u2 * u;
    const S h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    const float* p0 = v0 + width;       // value of k0
    const float* m0 = v0 + 2 * width;   // out-tangent of k0
    const float* p1 = v1 + width;       // value of k1
    const float* m1 = v1;               // in-tangent of k1
    for (int j = 0; j < width; ++j) out[j] = h00 * p0[j] + h10 * dt * m0[j] + h01 * p1[j] + h11 * dt * m1[j];
    THRONG_TALLY(ops, 7 + 6u * width, 6 + 3u * width, 0, 0);
    if (orientation) {
        const S n = sqrtOf(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
        THRONG_TALLY(ops, 4, 4, 0, 1);  // length, comparison
        if (n > S(0)) {
            for (int j = 0; j < 4; ++j) out[j] /= n;
            THRONG_TALLY(ops, 0, 0, 4, 0);
        }
    }
}

/// Writes channel `c`'s value at local time `t` into `out` (`width` values).
template <class S>
void sampleChannel(const ClipChannel& c, int width, bool orientation, S t, S* out, OpTally* ops, bool holdKeys) {
    sampleChannelAt(c, width, orientation, t, keyAfter(c.times, t, ops), out, ops, holdKeys);
}

/// Samples the node channels of `clip` (see AnimationClip::sample). A run of channels with the
/// same key times (AnimationClip::timeSources) searches them once.
template <class S>
std::size_t sampleClip(const AnimationClip& clip, const ActorTemplate& tmpl, Wide<S> t, bool loop,
                       std::span<const std::uint8_t> active, std::span<S> dofs, OpTally* ops, bool holdKeys) {
    const S ft = static_cast<S>(clipLocalTime(Wide<S>(clip.duration()), t, loop, ops));
    const auto channels = std::span<const ClipChannel>(clip.channels());
    const auto sources = clip.timeSources();
    std::size_t written = 0;
    std::uint32_t searched = ~std::uint32_t{0};  // the time source of the last search
    std::size_t upper = 0;
    for (std::size_t i = 0; i < channels.size(); ++i) {
        const ClipChannel& c = channels[i];
        const bool weight = c.target == ClipChannel::Target::MorphWeight;
        if (c.target != ClipChannel::Target::NodeDof && !weight) continue;
        if (!weight && !active.empty() && !active[c.node]) continue;  // inactive nodes are never evaluated
        if (sources[i] != searched) {
            searched = sources[i];
            upper = keyAfter(c.times, ft, ops);
        }
        if (weight) {
            sampleChannelAt(c, 1, false, ft, upper, dofs.data() + tmpl.morphWeightOffset() + c.node, ops, holdKeys);
            ++written;
            continue;
        }
        const DofKind kind = tmpl.dofKind(c.node, c.dof);
        const int width = dofValueCount(kind);
        sampleChannelAt(c, width, kind == DofKind::Orientation, ft, upper, dofs.data() + tmpl.dofValueOffset(c.node, c.dof),
                        ops, holdKeys);
        written += static_cast<std::size_t>(width);
    }
    return written;
}

/// Samples the Skeleton Root channels of `clip` (see AnimationClip::sampleRoot).
template <class S>
BasicRootPose<S> sampleClipRoot(const AnimationClip& clip, Wide<S> t, bool loop, OpTally* ops, bool holdKeys) {
    const S ft = static_cast<S>(clipLocalTime(Wide<S>(clip.duration()), t, loop, ops));
    BasicRootPose<S> root;
    for (const ClipChannel& c : clip.channels()) {
        if (c.target == ClipChannel::Target::RootTranslation) {
            sampleChannel(c, 3, false, ft, &root.translation.x, ops, holdKeys);
        } else if (c.target == ClipChannel::Target::RootOrientation) {
            S q[4];
            sampleChannel(c, 4, true, ft, q, ops, holdKeys);
            root.orientation = normalizeQuat(glm::qua<S, glm::defaultp>(q[3], q[0], q[1], q[2]), ops);
        }
    }
    return root;
}

}  // namespace throng::detail
