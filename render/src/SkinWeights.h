#pragma once
// Private: the per-vertex weight normalisation both skinning paths share (the CPU kernel uses it on
// every call, the GPU path once at upload), so that they blend exactly the same weights.

#include <cstddef>

#include <glm/vec4.hpp>

#include "throng/scenegraph/MeshData.h"

namespace throng::detail {

/// Weights of vertex `v` divided by their sum (4 or 8 influences; w1 is zero for 4). All zero when
/// the sum is zero: such a vertex keeps its bind position.
inline void normalisedWeights(const MeshData& mesh, std::size_t v, bool eight, glm::vec4& w0, glm::vec4& w1) {
    w0 = mesh.weights0[v];
    w1 = eight ? mesh.weights1[v] : glm::vec4(0.0f);
    float sum = (w0.x + w0.y) + (w0.z + w0.w);
    if (eight) sum += (w1.x + w1.y) + (w1.z + w1.w);
    if (sum == 0.0f) {
        w0 = w1 = glm::vec4(0.0f);
        return;
    }
    w0 /= sum;
    w1 /= sum;
}

}  // namespace throng::detail
