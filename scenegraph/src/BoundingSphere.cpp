#include "throng/scenegraph/BoundingSphere.h"

#include "throng/scenegraph/detail/BoundingSphereImpl.h"

namespace throng {

template class BasicBoundingSphere<double>;

double maxScaleFactor(const Mat4& m, OpTally* ops) { return detail::maxScaleFactor(m, ops); }

}  // namespace throng
