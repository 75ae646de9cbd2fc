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
    return s;  // width and height are checked by the buffer
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

const OcclusionStatistics& OcclusionCulling::build(Node& root, const Camera& camera, const Frustum& frustum) {
    Stopwatch watch;
    stats_ = OcclusionStatistics{};
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
