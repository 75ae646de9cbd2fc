#pragma once
// Traditional level of detail: the node computes its own distance from the eye to its centre every
// frame and shows the child whose range holds it. Children are ordered from the highest detail.

#include <vector>

#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/Math.h"
#include "throng/scenegraph/OpTally.h"

namespace throng {

/// A group showing one child chosen by the distance from the eye to the node's centre.
class LOD : public Group {
public:
    void accept(NodeVisitor& visitor) override;

    /// Appends `child`, shown while the distance is below `maxDistance` and at or above the
    /// previous child's. Throws std::invalid_argument if maxDistance is not finite, not positive,
    /// or not greater than the previous child's (or if addChild would throw).
    void addChild(std::shared_ptr<Node> child, double maxDistance);
    /// Distance up to which child `i` is shown.
    double maxDistance(std::size_t i) const { return maxDistances_.at(i); }

    /// Sets the centre (in the node's frame) whose distance to the eye selects the child.
    void setCenter(const Vec3& center);
    /// The centre in the node's frame (default: the origin).
    const Vec3& center() const { return center_; }

    /// Multiplies this node's eye distance on top of any visitor's LOD scale (finite, > 0; default
    /// 1). A scene keeps declared levels unused with a small scale until a frame budget asks for
    /// them. Throws std::invalid_argument otherwise.
    void setDistanceScale(double scale);
    /// This node's own distance multiplier.
    double distanceScale() const { return distanceScale_; }
    /// Its square (what the squared-distance selection multiplies by).
    double distanceScaleSquared() const { return distanceScale_ * distanceScale_; }

    /// Index of the child shown at `distance` (already multiplied by any LOD scale), or -1 if none.
    int selectChild(double distance) const;
    /// Index of the child shown when the squared distance is `distance2` (saves a sqrt), or -1.
    /// Its comparisons are added to `ops` if non-null (NO_05).
    int selectChildSquared(double distance2, OpTally* ops = nullptr) const;

private:
    using Group::addChild;  // children of an LOD need a range
    std::vector<double> maxDistances_;
    std::vector<double> maxDistances2_;
    Vec3 center_{0.0};
    double distanceScale_ = 1.0;
};

}  // namespace throng
