#include "throng/actors/RefpointPath.h"

#include "throng/actors/detail/RefpointKernel.h"

namespace throng {

Mat4 RefpointPath::at(double time, OpTally* ops) const {
    return detail::refpointMatrix(center, heading, radius, speed, time, ops);
}

}  // namespace throng
