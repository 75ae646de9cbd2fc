#pragma once
// A leaf that shows one Drawable in the frame of its nearest Transform ancestor.

#include <memory>

#include "throng/scenegraph/Drawable.h"
#include "throng/scenegraph/Node.h"

namespace throng {

/// A leaf referencing shared drawable data.
class Geometry : public Node {
public:
    /// A leaf showing `drawable` (throws std::invalid_argument if null).
    explicit Geometry(std::shared_ptr<const Drawable> drawable);
    void accept(NodeVisitor& visitor) override;

    /// The drawable shown.
    const Drawable& drawable() const { return *drawable_; }
    /// Shared handle to the drawable.
    const std::shared_ptr<const Drawable>& drawablePtr() const { return drawable_; }
    /// Replaces the drawable (throws std::invalid_argument if null).
    void setDrawable(std::shared_ptr<const Drawable> drawable);

private:
    std::shared_ptr<const Drawable> drawable_;
};

}  // namespace throng
