#include "throng/scenegraph/Geometry.h"

#include <stdexcept>

#include "throng/scenegraph/NodeVisitor.h"
#include "throng/scenegraph/Validation.h"

namespace throng {

Geometry::Geometry(std::shared_ptr<const Drawable> drawable) {
    if (!drawable) throw std::invalid_argument("Geometry: argument 'drawable' is null");
    drawable_ = std::move(drawable);
    setName(drawable_->name());
}

void Geometry::accept(NodeVisitor& visitor) { visitor.apply(*this); }

void Geometry::setDrawable(std::shared_ptr<const Drawable> drawable) {
    if (!drawable) throw std::invalid_argument(errorContext("Geometry::setDrawable", name()) + ": argument 'drawable' is null");
    drawable_ = std::move(drawable);
    dirtyBound();
}

}  // namespace throng
