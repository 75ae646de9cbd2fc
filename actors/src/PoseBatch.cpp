// computeModelTransformsBatch: nodeLocalTransform and compose (detail/PoseKernels.h) written over
// four float lanes with the compiler's vector extension, expression for expression, so that every
// lane rounds as the scalar kernel does. Sine and cosine stay scalar per lane (the C library's).

#include "throng/actors/detail/PoseBatch.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace throng::detail {
namespace {

using F4 = float __attribute__((vector_size(16)));  // GCC and Clang lower it to SSE (x86-64) or NEON (ARM)

F4 splat(float x) { return F4{x, x, x, x}; }

// Lane k of the batch reads its value at `offset` of its DOF values.
F4 gather(std::span<const PoseLane> lanes, std::uint32_t offset) {
    F4 v = splat(0.0f);
    for (std::size_t k = 0; k < lanes.size(); ++k) v[k] = lanes[k].dofs[offset];
    return v;
}

// std::clamp(v, lo, hi) lane by lane (NaN passes through, as there).
F4 clampLanes(F4 v, float lo, float hi) {
    const F4 l = splat(lo), h = splat(hi);
    return v < l ? l : (h < v ? h : v);
}

// A quaternion and an affine transform, lane by lane.
struct Quat4 {
    F4 w, x, y, z;
};
struct Affine4 {
    F4 m[3][3];  // [column][row], as glm
    F4 t[3];
};

// p * q, glm's formula term for term.
Quat4 multiply(const Quat4& p, const Quat4& q) {
    return {p.w * q.w - p.x * q.x - p.y * q.y - p.z * q.z, p.w * q.x + p.x * q.w + p.y * q.z - p.z * q.y,
            p.w * q.y + p.y * q.w + p.z * q.x - p.x * q.z, p.w * q.z + p.z * q.w + p.x * q.y - p.y * q.x};
}

// nodeLocalTransform over the lanes.
Affine4 localTransform(const SkeletonNode& node, std::span<const PoseLane> lanes, std::uint32_t offset) {
    F4 t[3] = {splat(node.restTranslation.x), splat(node.restTranslation.y), splat(node.restTranslation.z)};
    Quat4 r{splat(node.restRotation.w), splat(node.restRotation.x), splat(node.restRotation.y), splat(node.restRotation.z)};
    F4 s[3] = {splat(node.restScale.x), splat(node.restScale.y), splat(node.restScale.z)};
    for (const Dof& d : node.dofs) {
        switch (d.kind) {
            case DofKind::RotateAxis: {
                const F4 half = splat(0.5f) * clampLanes(gather(lanes, offset), d.min, d.max);
                F4 sn = splat(0.0f), cs = splat(1.0f);
                for (std::size_t k = 0; k < lanes.size(); ++k) {
                    sn[k] = std::sin(half[k]);
                    cs[k] = std::cos(half[k]);
                }
                r = multiply(r, Quat4{cs, splat(d.axis.x) * sn, splat(d.axis.y) * sn, splat(d.axis.z) * sn});
                break;
            }
            case DofKind::TranslateAxis: {
                const F4 v = clampLanes(gather(lanes, offset), d.min, d.max);
                for (int c = 0; c < 3; ++c) t[c] += splat(d.axis[c]) * v;
                break;
            }
            case DofKind::Orientation:
                r = multiply(r, Quat4{gather(lanes, offset + 3), gather(lanes, offset), gather(lanes, offset + 1),
                                      gather(lanes, offset + 2)});
                break;
            case DofKind::Position:
                for (std::uint32_t c = 0; c < 3; ++c) t[c] += gather(lanes, offset + c);
                break;
            case DofKind::Scale:
                for (std::uint32_t c = 0; c < 3; ++c) s[c] *= gather(lanes, offset + c);
                break;
        }
        offset += static_cast<std::uint32_t>(dofValueCount(d.kind));
    }
    const F4 one = splat(1.0f);
    const F4 x2 = r.x + r.x, y2 = r.y + r.y, z2 = r.z + r.z;
    const F4 xx = r.x * x2, xy = r.x * y2, xz = r.x * z2, yy = r.y * y2, yz = r.y * z2, zz = r.z * z2;
    const F4 wx = r.w * x2, wy = r.w * y2, wz = r.w * z2;
    Affine4 a;
    const F4 columns[3][3] = {{one - (yy + zz), xy + wz, xz - wy}, {xy - wz, one - (xx + zz), yz + wx}, {xz + wy, yz - wx, one - (xx + yy)}};
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row) a.m[c][row] = columns[c][row] * s[c];
    for (int c = 0; c < 3; ++c) a.t[c] = t[c];
    return a;
}

// p * b, glm's mat3 * mat3 and mat3 * vec3 term for term.
Affine4 compose(const Affine4& p, const Affine4& b) {
    Affine4 out;
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row) out.m[c][row] = p.m[0][row] * b.m[c][0] + p.m[1][row] * b.m[c][1] + p.m[2][row] * b.m[c][2];
    for (int row = 0; row < 3; ++row) out.t[row] = p.m[0][row] * b.t[0] + p.m[1][row] * b.t[1] + p.m[2][row] * b.t[2] + p.t[row];
    return out;
}

// The workspace holds a node's transform as 12 aligned lane groups.
void store(PoseBatchWorkspace::Lanes* to, const Affine4& a) {
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row) std::memcpy(to[3 * c + row].lane, &a.m[c][row], sizeof(F4));
    for (int row = 0; row < 3; ++row) std::memcpy(to[9 + row].lane, &a.t[row], sizeof(F4));
}
Affine4 load(const PoseBatchWorkspace::Lanes* from) {
    Affine4 a;
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row) std::memcpy(&a.m[c][row], from[3 * c + row].lane, sizeof(F4));
    for (int row = 0; row < 3; ++row) std::memcpy(&a.t[row], from[9 + row].lane, sizeof(F4));
    return a;
}

// Lanes (a[k], b[k], c[k], d[k]) as four vectors, k = 0..3: a 4x4 transpose.
void transpose(F4& a, F4& b, F4& c, F4& d) {
    const F4 t0 = __builtin_shufflevector(a, b, 0, 4, 1, 5), t1 = __builtin_shufflevector(a, b, 2, 6, 3, 7);
    const F4 t2 = __builtin_shufflevector(c, d, 0, 4, 1, 5), t3 = __builtin_shufflevector(c, d, 2, 6, 3, 7);
    a = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
    b = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
    c = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    d = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// Writes node i's transform of each live lane into that lane's model array: an Affine is 12
// consecutive floats (linear by columns, then translation), so three transposes turn the 12
// lane vectors into three stores per lane instead of twelve.
void scatter(const Affine4& a, std::span<const PoseLane> lanes, std::uint8_t live, std::size_t i) {
    static_assert(sizeof(Affine) == 12 * sizeof(float), "an Affine is 12 packed floats");
    F4 v[12] = {a.m[0][0], a.m[0][1], a.m[0][2], a.m[1][0], a.m[1][1], a.m[1][2],
                a.m[2][0], a.m[2][1], a.m[2][2], a.t[0],    a.t[1],    a.t[2]};
    for (int g = 0; g < 12; g += 4) transpose(v[g], v[g + 1], v[g + 2], v[g + 3]);
    for (std::size_t k = 0; k < lanes.size(); ++k) {
        if (!(live & (1u << k))) continue;
        auto* out = reinterpret_cast<unsigned char*>(&lanes[k].model[i]);
        // The lane's transforms a few nodes on, written soon (an integer address: it may lie past the array).
        __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(out) + 4 * sizeof(Affine)), 1);
        for (std::size_t g = 0; g < 3; ++g) std::memcpy(out + 16 * g, &v[4 * g + k], sizeof(F4));
    }
}

// The operations computeModelTransforms tallies for one node (see detail::nodeLocalTransform).
void tallyNode(const SkeletonNode& node, std::uint64_t lanes, OpTally* ops) {
#if THRONG_OP_COUNTING
    if (!ops) return;
    std::uint64_t m = 18, a = 15, q = 0;  // rotation to matrix
    for (const Dof& d : node.dofs) {
        switch (d.kind) {
            case DofKind::RotateAxis: m += 20, a += 14, q += 2; break;
            case DofKind::TranslateAxis: m += 3, a += 5; break;
            case DofKind::Orientation: m += 16, a += 12; break;
            case DofKind::Position: a += 3; break;
            case DofKind::Scale: m += 3; break;
        }
    }
    if (node.parent >= 0) m += 36, a += 27;
    THRONG_TALLY(ops, m * lanes, a * lanes, 0, q * lanes);
#else
    (void)node, (void)lanes, (void)ops;
#endif
}

}  // namespace

void computeModelTransformsBatch(const ActorTemplate& tmpl, std::span<const PoseLane> lanes, PoseBatchWorkspace& w,
                                 std::span<std::uint32_t> evaluated, OpTally* ops) {
    const auto nodes = tmpl.nodes();
    const std::size_t n = nodes.size();
    if (w.model.size() < 12 * n) w.model.resize(12 * n);
    if (w.live.size() < n) w.live.resize(n);
    const std::size_t count = std::min(lanes.size(), kPoseLanes);
    lanes = lanes.first(count);
    std::fill(evaluated.begin(), evaluated.begin() + static_cast<std::ptrdiff_t>(count), 0u);
    for (std::size_t i = 0; i < n; ++i) {
        // Lanes that compute node i: active, under a parent they computed.
        const int p = nodes[i].parent;
        std::uint8_t live = p < 0 ? std::uint8_t((1u << count) - 1u) : w.live[static_cast<std::size_t>(p)];
        for (std::size_t k = 0; k < count; ++k)
            if (lanes[k].active && !lanes[k].active[i]) live &= std::uint8_t(~(1u << k));
        w.live[i] = live;
        if (!live) {  // no lane computes it: its subtree is never visited
            i = tmpl.subtreeEnd(i) - 1;
            continue;
        }
        const Affine4 local = localTransform(nodes[i], lanes, tmpl.dofOffset(i));
        const Affine4 model = p < 0 ? local : compose(load(&w.model[12 * static_cast<std::size_t>(p)]), local);
        store(&w.model[12 * i], model);
        tallyNode(nodes[i], static_cast<std::uint64_t>(std::popcount(live)), ops);
        scatter(model, lanes, live, i);
        for (std::size_t k = 0; k < count; ++k) evaluated[k] += (live >> k) & 1u;
    }
}

}  // namespace throng::detail
