#include "throng/actors/ProceduralGait.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/RefpointPath.h"
#include "throng/scenegraph/Validation.h"

namespace throng {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// A fixed phase per DOF from its node and index (golden-ratio spacing), with left/right antiphase
// for nodes whose name starts with 'l' or 'r'.
double dofPhase(const SkeletonNode& node, std::size_t nodeIndex, std::size_t dof) {
    double phase = std::fmod(0.618034 * double(nodeIndex * 7 + dof), 1.0) * kTwoPi;
    if (!node.name.empty() && (node.name[0] == 'l' || node.name[0] == 'L')) phase = 0.0;
    if (!node.name.empty() && (node.name[0] == 'r' || node.name[0] == 'R')) phase = std::numbers::pi;
    return phase;
}

}  // namespace

ProceduralGait::ProceduralGait(std::vector<double> levelEnds) : levelEnds_(std::move(levelEnds)) {
    for (std::size_t i = 0; i < levelEnds_.size(); ++i)
        if (std::isnan(levelEnds_[i]) || levelEnds_[i] <= 0.0 || (i > 0 && levelEnds_[i] <= levelEnds_[i - 1]))
            throw std::invalid_argument("ProceduralGait: level ends must be positive and increasing");
}

std::uint32_t ProceduralGait::addActor(const Actor& a) {
    constexpr const char* where = "ProceduralGait::addActor";
    requireFinite(a.center, where, "actor.center");
    requireFinite(a.radius, where, "actor.radius");
    requireFinite(a.speed, where, "actor.speed");
    requireFinite(a.phase, where, "actor.phase");
    requireFinite(a.stepFrequency, where, "actor.stepFrequency");
    if (a.radius < 0.0 || a.stepFrequency < 0.0)
        throw std::invalid_argument(std::string(where) + ": radius and step frequency must not be negative");
    actors_.push_back(a);
    return static_cast<std::uint32_t>(actors_.size() - 1);
}

Mat4 ProceduralGait::referencePoint(std::uint32_t slot, const FrameContext& context, OpTally* ops) {
    const Actor& a = actors_[slot];
    return RefpointPath{a.center, a.phase, a.radius, a.speed}.at(context.time, ops);
}

RootPose ProceduralGait::skeletonRoot(std::uint32_t slot, double time, int level, OpTally* ops) {
    RootPose root;
    if (level != 0) return root;  // the bob is level-0 detail
    const Actor& a = actors_[slot];
    const double w = kTwoPi * a.stepFrequency;
    // Two bobs per stride, with a small second harmonic for the heel strike.
    const double bob = 0.5 * kBobHeight * (1.0 - std::cos(2.0 * w * time + a.phase)) +
                       0.1 * kBobHeight * std::sin(4.0 * w * time + a.phase);
    root.translation.y = static_cast<float>(bob);
    THRONG_TALLY(ops, 8, 3, 0, 2);
    return root;
}

void ProceduralGait::pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
                          std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) {
    const Actor& a = actors_[slot];
    const auto nodes = tmpl.nodes();
    const auto rest = tmpl.restDofs();
    const double w = kTwoPi * a.stepFrequency;
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
            const double lo = std::max<double>(dof.min, -1e3), hi = std::min<double>(dof.max, 1e3);
            const double amplitude = std::min(0.6, 0.5 * (hi - lo));
            const double phase = dofPhase(node, i, d) + a.phase;
            double signal = 0.0;
            for (int h = 0; h < harmonics; ++h) signal += kWeights[h] * std::sin((h + 1) * w * time + phase);
            THRONG_TALLY(ops, 3u * harmonics + 3, 2u * harmonics + 4, 0, static_cast<std::uint64_t>(harmonics));
            dofs[at] = static_cast<float>(std::clamp(double(dof.rest[0]) + amplitude * signal / 1.35, lo, hi));
        }
    }
}

BoundingSphere ProceduralGait::skeletonRootExtent(std::uint32_t) const {
    // The bob stays within [-0.1, 1.1] * kBobHeight on Y.
    return BoundingSphere(Vec3(0.0, 0.5 * kBobHeight, 0.0), 0.61 * kBobHeight + 1e-4);
}

}  // namespace throng
