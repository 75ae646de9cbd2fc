#pragma once
// The model transforms of several actors of one template at once, one actor per SIMD lane (in the
// manner of ozz-animation's SoA jobs). Both processing methods pose through it; each lane does the
// arithmetic of computeModelTransforms in the same order, so a lane's result is that function's to
// the bit (the compiler contracts neither: tests/actors/PoseBatchTest checks it).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/Affine.h"
#include "throng/scenegraph/OpTally.h"

namespace throng::detail {

/// Actors posed together: four float lanes, the SIMD width every x86-64 and ARMv8 CPU has.
inline constexpr std::size_t kPoseLanes = 4;

/// One actor of a batch.
struct PoseLane {
    const float* dofs = nullptr;            ///< its DOF values (the template's dofValueCount())
    const std::uint8_t* active = nullptr;   ///< its active-node flags, or null: every node
    Affine* model = nullptr;                ///< where its model transforms go (nodeCount() entries)
};

/// Scratch of computeModelTransformsBatch, kept between calls so that a warm frame allocates
/// nothing; one per thread.
struct PoseBatchWorkspace {
    /// Four lanes of one float, aligned as a SIMD register.
    struct alignas(16) Lanes {
        float lane[kPoseLanes];
    };
    std::vector<Lanes> model;           ///< per node, its 12 model-transform values, lane by lane
    std::vector<std::uint8_t> live;     ///< per node, a bit per lane: computed for that lane
};

/// computeModelTransforms for 1 to kPoseLanes actors of `tmpl` at once: lane k's active nodes
/// (whose ancestors are all active) get their model transforms in lanes[k].model, others are left
/// untouched, and evaluated[k] is set to how many were computed. Inputs are not checked (callers
/// hold spans of the right sizes). Operations are tallied into `ops` per node and lane, as
/// computeModelTransforms tallies them.
void computeModelTransformsBatch(const ActorTemplate& tmpl, std::span<const PoseLane> lanes, PoseBatchWorkspace& workspace,
                                 std::span<std::uint32_t> evaluated, OpTally* ops);

/// Poses actors [begin, end) in batches of up to kPoseLanes consecutive actors of one template:
/// `templateOf(k)` is actor k's template (a reference), `laneOf(k)` its PoseLane; `posed(k, n)` is
/// told that actor k had n nodes computed.
template <class TemplateOf, class LaneOf, class Posed>
void poseInBatches(std::size_t begin, std::size_t end, TemplateOf&& templateOf, LaneOf&& laneOf, PoseBatchWorkspace& workspace,
                   OpTally* ops, Posed&& posed) {
    for (std::size_t k = begin; k < end;) {
        const ActorTemplate& t = templateOf(k);
        PoseLane lanes[kPoseLanes];
        std::size_t count = 0;
        for (; count < kPoseLanes && k + count < end && &templateOf(k + count) == &t; ++count) lanes[count] = laneOf(k + count);
        std::uint32_t evaluated[kPoseLanes];
        computeModelTransformsBatch(t, std::span(lanes, count), workspace, std::span(evaluated, count), ops);
        for (std::size_t l = 0; l < count; ++l, ++k) posed(k, evaluated[l]);
    }
}

}  // namespace throng::detail
