#include "throng/scenegraph/OcclusionCulling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/NodeVisitor.h"
#include "throng/scenegraph/Occluder.h"
#include "throng/scenegraph/Stopwatch.h"

namespace throng {
namespace {

const OcclusionSettings& checked(const OcclusionSettings& s) {
    if (s.maxOccluders < 1)
        throw std::invalid_argument("OcclusionSettings: 'maxOccluders' must be at least 1, not " + std::to_string(s.maxOccluders));
    if (s.restFrames < 0 || s.restFrames > 1000)
        throw std::invalid_argument("OcclusionSettings: 'restFrames' must be in [0, 1000], not " + std::to_string(s.restFrames));
    if (!(s.restBelow >= 0.0 && s.restBelow <= 1.0))
        throw std::invalid_argument("OcclusionSettings: 'restBelow' must be in [0, 1], not " + std::to_string(s.restBelow));
    if (!(s.wakeDistance >= 0.0 && std::isfinite(s.wakeDistance)))
        throw std::invalid_argument("OcclusionSettings: 'wakeDistance' must be finite and not negative, not " +
                                    std::to_string(s.wakeDistance));
    if (!(s.wakeAngleDegrees >= 0.0 && s.wakeAngleDegrees <= 180.0))
        throw std::invalid_argument("OcclusionSettings: 'wakeAngleDegrees' must be in [0, 180], not " +
                                    std::to_string(s.wakeAngleDegrees));
    return s;  // width and height are checked by the buffer
}

// The camera's view direction in the world (the view matrix's -Z row).
Vec3 viewDirection(const Camera& camera) {
    const Mat4& v = camera.view();
    return glm::normalize(Vec3(-v[0][2], -v[1][2], -v[2][2]));
}

// Collects the Occluder nodes in the frustum, skipping generic subtrees outside it.
class Gatherer : public NodeVisitor {
public:
    Gatherer(const Frustum& frustum, std::vector<const Occluder*>& found) : frustum_(frustum), found_(found) {}
    void apply(Group& group) override {
        // A merged subtree without occluders (the tiles' meshes, their LOD levels) is not walked;
        // one changed since its bound was merged is, as before.
        if (!group.mayHoldOccluders() && !group.boundDirty()) return;
        const BoundingSphere& b = group.worldBound();
        if (b.valid() && frustum_.classify(b) == Containment::Outside) return;
        traverse(group);
    }
    void apply(Occluder& occluder) override {
        const BoundingSphere& b = occluder.worldOccluderBound();
        if (b.valid() && frustum_.classify(b) != Containment::Outside) found_.push_back(&occluder);
    }

private:
    const Frustum& frustum_;
    std::vector<const Occluder*>& found_;
};

}  // namespace

OcclusionCulling::OcclusionCulling(const OcclusionSettings& settings)
    : settings_(checked(settings)), buffer_(settings.width, settings.height) {}

bool OcclusionCulling::due(const Camera& camera) {
    builtThisFrame_ = false;
    if (restLeft_ > 0) {
        const bool moved = glm::length(camera.eye() - measuredEye_) > settings_.wakeDistance;
        const double cosTurn = glm::dot(viewDirection(camera), measuredView_);
        const bool turned = cosTurn < std::cos(glm::radians(settings_.wakeAngleDegrees));
        if (!moved && !turned) {
            --restLeft_;
            stats_ = OcclusionStatistics{};
            stats_.rested = true;
            return false;
        }
        restLeft_ = 0;
    }
    return true;
}

void OcclusionCulling::settle(std::uint64_t rejected, std::uint64_t tested) {
    if (!builtThisFrame_ || settings_.restFrames == 0) return;
    builtThisFrame_ = false;
    const bool little = tested == 0 || static_cast<double>(rejected) < settings_.restBelow * static_cast<double>(tested);
    if (little) restLeft_ = settings_.restFrames;
}

const OcclusionStatistics& OcclusionCulling::build(Node& root, const Camera& camera, const Frustum& frustum) {
    Stopwatch watch;
    stats_ = OcclusionStatistics{};
    restLeft_ = 0;
    builtThisFrame_ = true;
    measuredEye_ = camera.eye();
    measuredView_ = viewDirection(camera);
    buffer_.begin(camera);
    const Vec3 eye = camera.eye();
    found_.clear();
    Gatherer gather(frustum, found_);
    root.accept(gather);
    candidates_.clear();
    for (const Occluder* o : found_) {
        const BoundingSphere& b = o->worldOccluderBound();
        candidates_.push_back(Candidate{std::max(glm::length(b.center() - eye) - b.radius(), 0.0), o});
    }
    stats_.occludersInView = candidates_.size();
    std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
    const double margin = 2.0 * buffer_.nearReach();  // where the near plane may cut a shell open
    for (const Candidate& c : candidates_) {
        if (stats_.occludersDrawn >= static_cast<std::uint64_t>(settings_.maxOccluders)) break;
        if (c.occluder->shellContains(eye, margin)) {
            ++stats_.occludersInsideShell;
            continue;
        }
        ++stats_.occludersDrawn;
        for (std::size_t i = 0; i < c.occluder->boxes().size(); ++i)
            if (buffer_.drawBox(c.occluder->worldCorners(i))) ++stats_.boxesDrawn;
    }
    buffer_.finish();
    stats_.pixelsWritten = buffer_.pixelsWritten();
    stats_.bufferMs = watch.elapsedMs();
    return stats_;
}

}  // namespace throng
