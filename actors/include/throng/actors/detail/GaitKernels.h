#pragma once
// ProceduralGait's DOF values (the Skeleton Root's bob, each rotation swinging with harmonics),
// written once over the scalar type: ProceduralGait.cpp compiles them for float DOF values and
// double time, the FMULT tests for a counting type. Sine is priced as a square root, fmod as a
// division, a comparison as an addition (std::min and std::max make one, std::clamp two).

#include <algorithm>
#include <cstdint>
#include <numbers>
#include <span>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/ProceduralGait.h"
#include "throng/scenegraph/OpTally.h"
#include "throng/scenegraph/detail/ScalarMath.h"

namespace throng::detail {

/// 2 pi.
inline constexpr double kGaitTwoPi = 2.0 * std::numbers::pi;

/// Height of the Skeleton Root's bob at `time` for a stride of `stepFrequency` (level 0): 7 mults,
/// 4 adds, 2 sines.
template <class W>
W gaitBob(W stepFrequency, W phase, W time, OpTally* ops) {
    constexpr double h = ProceduralGait::kBobHeight;
    const W w = W(kGaitTwoPi) * stepFrequency;
    // Two bobs per stride, with a small second harmonic for the heel strike.
    THRONG_TALLY(ops, 7, 4, 0, 2);
    return W(0.5 * h) * (W(1.0) - cosOf(W(2.0) * w * time + phase)) + W(0.1 * h) * sinOf(W(4.0) * w * time + phase);
}

/// A fixed phase per DOF from its node and index (golden-ratio spacing), with left/right antiphase
/// for nodes whose name starts with 'l' or 'r' (2 mults and an fmod, computed either way).
template <class W>
W gaitDofPhase(const SkeletonNode& node, std::size_t nodeIndex, std::size_t dof) {
    W phase = fmodOf(W(0.618034) * W(double(nodeIndex * 7 + dof)), W(1.0)) * W(kGaitTwoPi);
    if (!node.name.empty() && (node.name[0] == 'l' || node.name[0] == 'L')) phase = W(0.0);
    if (!node.name.empty() && (node.name[0] == 'r' || node.name[0] == 'R')) phase = W(std::numbers::pi);
    return phase;
}

/// DOF values of the active nodes of `tmpl` for `actor` at `time` and precision `level` (see
/// ProceduralGait::pose): per swinging DOF 3h + 4 mults, 2h + 8 adds, 2 divisions and h sines for h
/// harmonics; other DOFs keep their rest values.
template <class S>
void gaitPose(const ProceduralGait::Actor& actor, Wide<S> time, int level, const ActorTemplate& tmpl,
              std::span<const std::uint8_t> active, std::span<S> dofs, OpTally* ops) {
    using W = Wide<S>;
    const auto nodes = tmpl.nodes();
    const auto rest = tmpl.restDofs();
    const W w = W(kGaitTwoPi) * W(actor.stepFrequency);
    THRONG_TALLY(ops, 1, 0, 0, 0);
    const int harmonics = level == 0 ? 3 : level == 1 ? 1 : 0;  // beyond the last band: rest pose
    constexpr double kWeights[3] = {1.0, 0.25, 0.1};
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (!active.empty() && !active[i]) {
            i = tmpl.subtreeEnd(i) - 1;
            continue;
        }
        const SkeletonNode& node = nodes[i];
        for (std::size_t d = 0; d < node.dofs.size(); ++d) {
            const Dof& dof = node.dofs[d];
            const std::uint32_t at = tmpl.dofValueOffset(i, d);
            if (dof.kind != DofKind::RotateAxis || harmonics == 0) {
                for (int k = 0; k < dofValueCount(dof.kind); ++k)
                    dofs[at + static_cast<std::uint32_t>(k)] = rest[at + static_cast<std::uint32_t>(k)];
                continue;
            }
            // Swing about the rest value, within the limits, never more than 0.6 rad.
            const W lo = std::max<W>(W(dof.min), W(-1e3)), hi = std::min<W>(W(dof.max), W(1e3));
            const W amplitude = std::min(W(0.6), W(0.5) * (hi - lo));
            const W phase = gaitDofPhase<W>(node, i, d) + W(actor.phase);
            W signal = W(0.0);
            for (int h = 0; h < harmonics; ++h) signal += W(kWeights[h]) * sinOf(W(h + 1) * w * time + phase);
            THRONG_TALLY(ops, 3u * harmonics + 4, 2u * harmonics + 8, 2, static_cast<std::uint64_t>(harmonics));
            dofs[at] = static_cast<S>(std::clamp(W(dof.rest[0]) + amplitude * signal / W(1.35), lo, hi));
        }
    }
}

}  // namespace throng::detail
