#include "throng/sim/ClipBlend.h"

#include <cmath>

namespace throng::sim {

void blendPoses(const ActorTemplate& tmpl, std::span<const float> a, std::span<const float> b, float w,
                std::span<const std::uint8_t> active, std::span<float> out) {
    const auto nodes = tmpl.nodes();
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (!active.empty() && !active[i]) continue;
        for (std::size_t d = 0; d < nodes[i].dofs.size(); ++d) {
            const std::uint32_t o = tmpl.dofValueOffset(i, d);
            if (nodes[i].dofs[d].kind == DofKind::Orientation) {
                // q and -q are the same rotation: blend along the short way, then renormalize.
                const float dot = a[o] * b[o] + a[o + 1] * b[o + 1] + a[o + 2] * b[o + 2] + a[o + 3] * b[o + 3];
                const float sign = dot < 0.0f ? -1.0f : 1.0f;
                float q[4], len = 0.0f;
                for (int k = 0; k < 4; ++k) {
                    q[k] = (1.0f - w) * a[o + k] + w * sign * b[o + k];
                    len += q[k] * q[k];
                }
                len = std::sqrt(len);
                for (int k = 0; k < 4; ++k) out[o + k] = len > 0.0f ? q[k] / len : a[o + k];
            } else {
                for (int k = 0; k < dofValueCount(nodes[i].dofs[d].kind); ++k)
                    out[o + k] = (1.0f - w) * a[o + k] + w * b[o + k];
            }
        }
    }
}

}  // namespace throng::sim
