#include "throng/scenegraph/TraditionalProcessor.h"

#include <stdexcept>

#include "throng/scenegraph/AppVisitor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/CullVisitor.h"
#include "throng/scenegraph/DrawBackend.h"
#include "throng/scenegraph/MatrixBoundsVisitor.h"
#include "throng/scenegraph/Node.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/scenegraph/Validation.h"

namespace throng {

void TraditionalProcessor::setLodScale(double scale) {
    requireFinite(scale, "TraditionalProcessor::setLodScale", "scale");
    if (!(scale > 0.0))
        throw std::invalid_argument("TraditionalProcessor::setLodScale: argument 'scale' must be positive");
    lodScale_ = scale;
}

void TraditionalProcessor::setOcclusion(const std::optional<OcclusionSettings>& settings) {
    if (settings) occlusion_.emplace(*settings);
    else occlusion_.reset();
}

const FrameStatistics& TraditionalProcessor::processFrame(Node& root, const Camera& camera, double time,
                                                          DrawBackend* backend) {
    requireFinite(time, "TraditionalProcessor::processFrame", "time");
    OpCounter* counter = counter_.enabled() ? &counter_ : nullptr;
    counter_.reset();
    stats_ = FrameStatistics{};
    stats_.frame = frame_;
    const FrameContext context{time, frame_ == 0 ? 0.0 : time - lastTime_, frame_, counter};

    Stopwatch watch;
    AppVisitor app(context);
    root.accept(app);
    stats_.appMs = watch.elapsedMs();
    stats_.callbacksRun = app.callbacksRun();

    watch.restart();
    MatrixBoundsVisitor matrices(counter, fullRecompute_);
    root.accept(matrices);
    stats_.matricesBoundsMs = watch.elapsedMs();
    stats_.matrices = matrices.statistics();

    // A stage that rests this frame (the last one rejected little) builds and tests nothing.
    const bool occluding = occlusion_ && occlusion_->due(camera);
    if (occluding) stats_.occlusion = occlusion_->build(root, camera, cullingFrustum_ ? *cullingFrustum_ : camera.frustum());
    else if (occlusion_) stats_.occlusion = occlusion_->statistics();

    watch.restart();
    current_ = 1 - current_;  // the previous frame's list stays intact for a DRAW still reading it
    DrawList& list = drawLists_[current_];
    list.clear();
    CullVisitor cull(camera, list, counter, lodScale_);
    if (cullingFrustum_) cull.setCullingFrustum(*cullingFrustum_);
    cull.setFrameTime(time);
    if (occluding) cull.setOcclusion(&occlusion_->buffer());
    root.accept(cull);
    stats_.cullMs = watch.elapsedMs();
    stats_.cull = cull.statistics();
    if (occluding) occlusion_->settle(stats_.cull.nodesOccluded, stats_.cull.occlusionTests);

    if (backend) {
        watch.restart();
        backend->drawFrame(camera, list);
        stats_.drawMs = watch.elapsedMs();
    }
    stats_.fmultTotal = counter ? counter_.totalFmult() : 0;
    lastTime_ = time;
    ++frame_;
    return stats_;
}

}  // namespace throng
