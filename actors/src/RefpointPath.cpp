#include "throng/actors/RefpointPath.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "throng/actors/detail/RefpointKernel.h"

namespace throng {

Mat4 RefpointPath::at(double time, OpTally* ops) const {
    return detail::refpointMatrix(center, heading, radius, speed, time, ops);
}

void RefpointPath::atEach(std::span<const RefpointPath> paths, double time, std::span<Mat4> out, OpTally* ops) {
    if (out.size() < paths.size()) [[unlikely]]
        throw std::invalid_argument("RefpointPath::atEach: argument 'out' holds " + std::to_string(out.size()) +
                                    " matrices, less than the " + std::to_string(paths.size()) + " paths");
    constexpr std::size_t kBlock = 16;  // angles on the stack, a few cache lines
    double angles[kBlock], sines[kBlock], cosines[kBlock];
    bool onCircle[kBlock];
    for (std::size_t first = 0; first < paths.size(); first += kBlock) {
        const std::size_t n = std::min(kBlock, paths.size() - first);
        for (std::size_t k = 0; k < n; ++k) {
            const RefpointPath& p = paths[first + k];
            onCircle[k] = detail::refpointOnCircle(p.radius, ops);
            angles[k] = detail::refpointAngle(p.heading, p.radius, p.speed, time, onCircle[k], ops);
        }
        detail::sinCos(angles, sines, cosines, n);
        for (std::size_t k = 0; k < n; ++k) {
            const RefpointPath& p = paths[first + k];
            out[first + k] = detail::refpointFromSinCos(p.center, p.radius, onCircle[k], sines[k], cosines[k], ops);
        }
    }
}

}  // namespace throng
